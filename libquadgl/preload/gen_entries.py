#!/usr/bin/env python3
"""gen_entries.py: writes the preload library's GL dispatch (pl_entries.h, pl_entries.c).

The library handles a few hundred GL entry points that differ only in argument types
(glColor3ub, glTexCoord2dv, ...). Each one gets three generated pieces: a slot holding the
real driver's function, resolved lazily by a per-slot stub on its first call; an exported
wrapper that calls the slot directly unless a quad primitive is being captured, in which
case it converts its arguments to floats and hands them to the capture layer; and a row in
a sorted name table that glXGetProcAddress and friends search. Entry points written by hand
(glBegin, the draws, the lists) get a slot and a table row here and their bodies in C.
Functions the library only calls (glGetFloatv, ...) get a slot alone.

Usage: gen_entries.py OUT.h OUT.c
"""
import sys

# (suffix, C type, float conversion of a colour or normal component, plain conversion)
TYPES = {
    'b': ('GLbyte', 'PL_B({})', '(float)({})'),
    'ub': ('GLubyte', 'PL_UB({})', '(float)({})'),
    's': ('GLshort', 'PL_S({})', '(float)({})'),
    'us': ('GLushort', 'PL_US({})', '(float)({})'),
    'i': ('GLint', 'PL_I({})', '(float)({})'),
    'ui': ('GLuint', 'PL_UI({})', '(float)({})'),
    'f': ('GLfloat', '({})', '({})'),
    'd': ('GLdouble', '(float)({})', '(float)({})'),
}

entries = []   # (ret, name, [(ctype, pname)], body or None, exported)


def add(name, params, body, ret='void', exported=True):
    entries.append((ret, name, params, body, exported))


def scalar_and_vector(base, n, t, comps, call, pad, conv_kind, lead=()):
    """The scalar and the v form of one attribute setter. call(args) gives the capture call
    from a list of C float expressions; pad fills missing components."""
    ctype, cconv, pconv = TYPES[t]
    conv = cconv if conv_kind == 'norm' else pconv
    names = comps[:n]
    lead_params = list(lead)
    lead_names = [p[1] for p in lead]
    params = lead_params + [(ctype, c) for c in names]
    vals = [conv.format(c) for c in names] + pad[n:]
    add(f'{base}{n}{t}', params, call(lead_names, vals))
    vparams = lead_params + [(f'const {ctype} *', 'v')]
    vvals = [conv.format(f'v[{i}]') for i in range(n)] + pad[n:]
    add(f'{base}{n}{t}v', vparams, call(lead_names, vvals))


def capture_call(fn):
    return lambda lead, vals: f'{fn}(cx, {", ".join(list(lead) + vals)});'


# glVertex{2,3,4}{s,i,f,d}{,v}
for n in (2, 3, 4):
    for t in ('s', 'i', 'f', 'd'):
        scalar_and_vector('glVertex', n, t, ['x', 'y', 'z', 'w'], capture_call('pl_cap_vertex'),
                          ['0', '0', '0.0f', '1.0f'], 'plain')

# glColor{3,4}{b,s,i,f,d,ub,us,ui}{,v}
for n in (3, 4):
    for t in ('b', 's', 'i', 'f', 'd', 'ub', 'us', 'ui'):
        scalar_and_vector('glColor', n, t, ['red', 'green', 'blue', 'alpha'],
                          capture_call('pl_cap_color'), ['0', '0', '0', '1.0f'], 'norm')

# glSecondaryColor3{...}{,v} and the EXT names
for suffix in ('', 'EXT'):
    for t in ('b', 's', 'i', 'f', 'd', 'ub', 'us', 'ui'):
        before = len(entries)
        scalar_and_vector('glSecondaryColor', 3, t, ['red', 'green', 'blue'],
                          capture_call('pl_cap_secondary'), [], 'norm')
        if suffix:
            for k in range(before, len(entries)):
                r, nm, p, b, e = entries[k]
                entries[k] = (r, nm + suffix, p, b, e)

# glNormal3{b,s,i,f,d}{,v}
for t in ('b', 's', 'i', 'f', 'd'):
    scalar_and_vector('glNormal', 3, t, ['nx', 'ny', 'nz'], capture_call('pl_cap_normal'), [], 'norm')

# glTexCoord{1,2,3,4}{s,i,f,d}{,v}: unit 0
for n in (1, 2, 3, 4):
    for t in ('s', 'i', 'f', 'd'):
        scalar_and_vector('glTexCoord', n, t, ['s', 't', 'r', 'q'],
                          lambda lead, vals: f'pl_cap_texcoord(cx, 0, {", ".join(vals)});',
                          ['0', '0.0f', '0.0f', '1.0f'], 'plain')

# glMultiTexCoord{1,2,3,4}{s,i,f,d}{,v} and the ARB names
for suffix in ('', 'ARB'):
    for n in (1, 2, 3, 4):
        for t in ('s', 'i', 'f', 'd'):
            before = len(entries)
            scalar_and_vector('glMultiTexCoord', n, t, ['s', 't', 'r', 'q'],
                              lambda lead, vals: f'pl_cap_texcoord(cx, {lead[0]} - GL_TEXTURE0, {", ".join(vals)});',
                              ['0', '0.0f', '0.0f', '1.0f'], 'plain', lead=[('GLenum', 'target')])
            if suffix:
                for k in range(before, len(entries)):
                    r, nm, p, b, e = entries[k]
                    entries[k] = (r, nm + suffix, p, b, e)

# glFogCoord{f,d}{,v} and EXT
for suffix in ('', 'EXT'):
    add(f'glFogCoordf{suffix}', [('GLfloat', 'coord')], 'pl_cap_fog(cx, coord);')
    add(f'glFogCoordd{suffix}', [('GLdouble', 'coord')], 'pl_cap_fog(cx, (float)coord);')
    add(f'glFogCoordfv{suffix}', [('const GLfloat *', 'coord')], 'pl_cap_fog(cx, coord[0]);')
    add(f'glFogCoorddv{suffix}', [('const GLdouble *', 'coord')], 'pl_cap_fog(cx, (float)coord[0]);')

add('glEdgeFlag', [('GLboolean', 'flag')], 'pl_cap_edgeflag(cx, flag);')
add('glEdgeFlagv', [('const GLboolean *', 'flag')], 'pl_cap_edgeflag(cx, flag[0]);')

add('glMaterialf', [('GLenum', 'face'), ('GLenum', 'pname'), ('GLfloat', 'param')],
    'pl_cap_material(cx, face, pname, &param);')
add('glMaterialfv', [('GLenum', 'face'), ('GLenum', 'pname'), ('const GLfloat *', 'params')],
    'pl_cap_material(cx, face, pname, params);')
add('glMateriali', [('GLenum', 'face'), ('GLenum', 'pname'), ('GLint', 'param')],
    'pl_cap_materiali(cx, face, pname, &param);')
add('glMaterialiv', [('GLenum', 'face'), ('GLenum', 'pname'), ('const GLint *', 'params')],
    'pl_cap_materiali(cx, face, pname, params);')

add('glArrayElement', [('GLint', 'i')], 'pl_cap_array_element(cx, i);')
add('glArrayElementEXT', [('GLint', 'i')], 'pl_cap_array_element(cx, i);')

# Written by hand in C: slot and table row only.
MANUAL = [
    ('void', 'glBegin', [('GLenum', 'mode')]),
    ('void', 'glEnd', []),
    ('void', 'glNewList', [('GLuint', 'list'), ('GLenum', 'mode')]),
    ('void', 'glEndList', []),
    ('void', 'glCallList', [('GLuint', 'list')]),
    ('void', 'glCallLists', [('GLsizei', 'n'), ('GLenum', 'type'), ('const void *', 'lists')]),
    ('void', 'glDeleteLists', [('GLuint', 'list'), ('GLsizei', 'range')]),
    ('void', 'glDrawArrays', [('GLenum', 'mode'), ('GLint', 'first'), ('GLsizei', 'count')]),
    ('void', 'glDrawArraysEXT', [('GLenum', 'mode'), ('GLint', 'first'), ('GLsizei', 'count')]),
    ('void', 'glDrawElements', [('GLenum', 'mode'), ('GLsizei', 'count'), ('GLenum', 'type'),
                                ('const void *', 'indices')]),
    ('void', 'glDrawRangeElements', [('GLenum', 'mode'), ('GLuint', 'start'), ('GLuint', 'end'),
                                     ('GLsizei', 'count'), ('GLenum', 'type'), ('const void *', 'indices')]),
    ('void', 'glDrawRangeElementsEXT', [('GLenum', 'mode'), ('GLuint', 'start'), ('GLuint', 'end'),
                                        ('GLsizei', 'count'), ('GLenum', 'type'), ('const void *', 'indices')]),
    ('void', 'glMultiDrawArrays', [('GLenum', 'mode'), ('const GLint *', 'first'),
                                   ('const GLsizei *', 'count'), ('GLsizei', 'drawcount')]),
    ('void', 'glMultiDrawArraysEXT', [('GLenum', 'mode'), ('const GLint *', 'first'),
                                      ('const GLsizei *', 'count'), ('GLsizei', 'drawcount')]),
    ('void', 'glMultiDrawElements', [('GLenum', 'mode'), ('const GLsizei *', 'count'), ('GLenum', 'type'),
                                     ('const void *const *', 'indices'), ('GLsizei', 'drawcount')]),
    ('void', 'glMultiDrawElementsEXT', [('GLenum', 'mode'), ('const GLsizei *', 'count'), ('GLenum', 'type'),
                                        ('const void *const *', 'indices'), ('GLsizei', 'primcount')]),
    ('void', 'glEvalMesh2', [('GLenum', 'mode'), ('GLint', 'i1'), ('GLint', 'i2'), ('GLint', 'j1'),
                             ('GLint', 'j2')]),
    ('void', 'glEvalCoord1f', [('GLfloat', 'u')]),
    ('void', 'glEvalCoord1d', [('GLdouble', 'u')]),
    ('void', 'glEvalCoord1fv', [('const GLfloat *', 'u')]),
    ('void', 'glEvalCoord1dv', [('const GLdouble *', 'u')]),
    ('void', 'glEvalCoord2f', [('GLfloat', 'u'), ('GLfloat', 'v')]),
    ('void', 'glEvalCoord2d', [('GLdouble', 'u'), ('GLdouble', 'v')]),
    ('void', 'glEvalCoord2fv', [('const GLfloat *', 'u')]),
    ('void', 'glEvalCoord2dv', [('const GLdouble *', 'u')]),
    ('void', 'glEvalPoint1', [('GLint', 'i')]),
    ('void', 'glEvalPoint2', [('GLint', 'i'), ('GLint', 'j')]),
]
for ret, name, params in MANUAL:
    add(name, params, None, ret)

# Called by the library, never exported.
IMPORTS = [
    ('void', 'glGetFloatv', [('GLenum', 'pname'), ('GLfloat *', 'data')]),
    ('void', 'glGetIntegerv', [('GLenum', 'pname'), ('GLint *', 'data')]),
    ('void', 'glGetPointerv', [('GLenum', 'pname'), ('void **', 'params')]),
    ('GLboolean', 'glIsEnabled', [('GLenum', 'cap')]),
    ('GLboolean', 'glIsList', [('GLuint', 'list')]),
    ('void', 'glGetVertexAttribiv', [('GLuint', 'index'), ('GLenum', 'pname'), ('GLint *', 'params')]),
    ('void', 'glGetMaterialfv', [('GLenum', 'face'), ('GLenum', 'pname'), ('GLfloat *', 'params')]),
    ('void', 'glActiveTexture', [('GLenum', 'texture')]),
    ('void', 'glClientActiveTexture', [('GLenum', 'texture')]),
    ('void', 'glBindBuffer', [('GLenum', 'target'), ('GLuint', 'buffer')]),
    ('void', 'glGetBufferSubData', [('GLenum', 'target'), ('GLintptr', 'offset'), ('GLsizeiptr', 'size'),
                                    ('void *', 'data')]),
    ('void', 'glVertex4fv', [('const GLfloat *', 'v')]),
    ('void', 'glColor4fv', [('const GLfloat *', 'v')]),
    ('void', 'glSecondaryColor3fv', [('const GLfloat *', 'v')]),
    ('void', 'glNormal3fv', [('const GLfloat *', 'v')]),
    ('void', 'glMultiTexCoord4fv', [('GLenum', 'target'), ('const GLfloat *', 'v')]),
    ('void', 'glFogCoordf', [('GLfloat', 'coord')]),
    ('void', 'glEdgeFlag', [('GLboolean', 'flag')]),
    ('void', 'glMaterialfv', [('GLenum', 'face'), ('GLenum', 'pname'), ('const GLfloat *', 'params')]),
    ('void', 'glGetMapiv', [('GLenum', 'target'), ('GLenum', 'query'), ('GLint *', 'v')]),
    ('void', 'glGetMapfv', [('GLenum', 'target'), ('GLenum', 'query'), ('GLfloat *', 'v')]),
]

# Slots are shared by name: an import that is also exported uses the exported one's slot.
exported_names = {e[1] for e in entries}
for ret, name, params in IMPORTS:
    if name not in exported_names:
        add(name, params, None, ret, exported=False)


def proto(params):
    return ', '.join(f'{t} {n}' if not t.endswith('*') else f'{t}{n}' for t, n in params) or 'void'


def args(params):
    return ', '.join(n for _, n in params)


def main():
    out_h, out_c = sys.argv[1], sys.argv[2]
    h = ['/* Generated by gen_entries.py: the real-driver slots of the preload library. */',
         '#ifndef PL_ENTRIES_H', '#define PL_ENTRIES_H', '', 'enum pl_slot {']
    for _, name, _, _, _ in entries:
        h.append(f'    PL_{name},')
    h += ['    PL_SLOT_COUNT', '};', '']
    for ret, name, params, _, _ in entries:
        h.append(f'typedef {ret} (*PFN_pl_{name})({proto(params)});')
    h += ['', 'extern void *pl_real_slot[PL_SLOT_COUNT];',
          'extern void *const pl_none_slot[PL_SLOT_COUNT];',
          'extern const char *const pl_slot_name[PL_SLOT_COUNT];',
          '/* The real driver function of a slot (resolved on first call). */',
          '#define REAL(name) ((PFN_pl_##name)pl_real_slot[PL_##name])',
          '', '#endif', '']

    c = ['/* Generated by gen_entries.py: lazy real-driver slots, exported capture wrappers and the',
         ' * name table of the preload library. Do not edit. */',
         '#include "preload.h"', '']
    c.append('const char *const pl_slot_name[PL_SLOT_COUNT] = {')
    for _, name, _, _, _ in entries:
        c.append(f'    "{name}",')
    c += ['};', '']
    # Lazy stubs: resolve the slot, then call through it.
    for ret, name, params, _, _ in entries:
        ret_kw = '' if ret == 'void' else 'return '
        c.append(f'static {ret} pl_lazy_{name}({proto(params)})')
        c.append('{')
        c.append(f'    pl_resolve_slot(PL_{name});')
        c.append(f'    {ret_kw}REAL({name})({args(params)});')
        c.append('}')
    # Stand-ins for functions no driver provides: do nothing, return zero.
    for ret, name, params, _, _ in entries:
        c.append(f'static {ret} pl_none_{name}({proto(params)})')
        c.append('{')
        c.append('    return' + ('' if ret == 'void' else ' 0') + ';')
        c.append('}')
    c += ['', 'void *const pl_none_slot[PL_SLOT_COUNT] = {']
    for _, name, _, _, _ in entries:
        c.append(f'    (void *)pl_none_{name},')
    c += ['};', '']
    c += ['', 'void *pl_real_slot[PL_SLOT_COUNT] = {']
    for _, name, _, _, _ in entries:
        c.append(f'    (void *)pl_lazy_{name},')
    c += ['};', '']
    # Exported wrappers.
    for ret, name, params, body, exported in entries:
        if body is None:
            continue
        c.append(f'PL_EXPORT void {name}({proto(params)})')
        c.append('{')
        c.append('    pl_ctx *cx = pl_capturing();')
        c.append('    if (PL_LIKELY(cx == NULL)) {')
        c.append(f'        REAL({name})({args(params)});')
        c.append('        return;')
        c.append('    }')
        c.append(f'    {body}')
        c.append('}')
        c.append('')
    # Sorted name table of everything exported (for GetProcAddress and dlsym redirection).
    rows = sorted((name for _, name, _, _, exported in entries if exported))
    c.append('const pl_proc pl_proc_table[] = {')
    for name in rows:
        c.append(f'    {{"{name}", (void *){name}}},')
    c += ['};', f'const int pl_proc_count = {len(rows)};', '']
    with open(out_h, 'w') as f:
        f.write('\n'.join(h))
    with open(out_c, 'w') as f:
        f.write('\n'.join(c))


main()
