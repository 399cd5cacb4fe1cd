#!/usr/bin/env python3
"""gen_entries.py: writes the preload library's GL dispatch (pl_entries.h, pl_entries.c).

The library exports every GL entry point the system's GL headers declare, so that it sees
every call a program makes: that is what lets it keep the state the planner needs up to date
from the calls that change it, instead of asking the driver at every draw. Each entry point
gets a slot holding the real driver function (resolved lazily by a per-slot stub on its first
call), a row in a sorted name table that glXGetProcAddress and friends search, and, unless
its body is written by hand in C, an exported wrapper of one of two kinds:

- attribute and vertex calls (glColor3ub, glTexCoord2dv, glVertexAttrib4Nubv, ...) convert
  their arguments to floats and hand them to a hook, which captures them inside a captured
  quad primitive and otherwise records the new current value before the driver gets the call;
- every other call marks, before the driver gets it, which groups of the tracked state it may
  change (RULES below: matrices, rasterization, the fixed-function key, bindings, current
  attributes); pure state queries mark nothing.

Inside a captured glBegin/glEnd a call GL does not allow there raises the driver's own
GL_INVALID_OPERATION and has no other effect, as it would natively; a call GL allows there
that the capture does not represent (UNCAPTURED) hands the primitive to the driver first.

Usage: gen_entries.py PROTOS OUT.h OUT.c, PROTOS being the preprocessed GL headers (gl.h and
glext.h with GL_GLEXT_PROTOTYPES).
"""
import re
import sys

# (suffix, C type, float conversion of a normalized component, plain conversion)
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

# Dirty groups (preload.h's PL_D_*), by name in RULES.
GROUPS = {'XFORM': 'PL_D_XFORM', 'RASTER': 'PL_D_RASTER', 'FFP': 'PL_D_FFP', 'BIND': 'PL_D_BIND', 'ORDER': 'PL_D_ORDER',
          'TEX': 'PL_D_TEX', 'TEXIMAGE': 'PL_D_TEXIMAGE', 'CURRENT': 'PL_D_CURRENT', 'LIST_BASE': 'PL_D_LIST_BASE'}

# What a call may change, first match wins. None: a pure query of state (nothing to mark, no
# pending quads to draw first); '': no tracked state, but the call may see the picture.
RULES = [
    (r'^gl(Get|Is)(?!n?(Compressed)?Tex(ture)?(Sub)?Image|(Named)?BufferSubData|Query(Object|Buffer|Indexed)|'
     r'Sync|n?ColorTable|n?Histogram|n?Minmax|n?Convolution|n?Separable)', None),
    (r'^gl(Uniform|ProgramUniform)', None),
    (r'^glPopAttrib$', 'XFORM RASTER FFP ORDER CURRENT LIST_BASE'),
    (r'^gl(DepthMask|DepthFunc|BindFramebuffer(EXT)?)$', 'ORDER'),
    (r'^gl(Enablei|Disablei|EnableIndexedEXT|DisableIndexedEXT)$', 'FFP ORDER'),
    (r'^gl(LoadIdentity|(Load|Mult)(Transpose)?Matrix[fd](ARB)?|Rotate[fd]|Translate[fd]|Scale[fd]|Frustum|Ortho|'
     r'PopMatrix|Viewport\w*|Matrix(Load|Mult|Rotate|Scale|Translate|Frustum|Ortho|Pop)\w*EXT)$', 'XFORM'),
    (r'^gl(ShadeModel|PolygonMode|RenderMode|UseProgram|UseProgramObjectARB|BindProgramPipeline|'
     r'ProvokingVertex(EXT)?|ClampColor(ARB)?|ActiveTexture(ARB)?)$', 'RASTER'),
    (r'^gl(BindTextures?(EXT)?|BindTextureUnit|BindMultiTextureEXT)$', 'TEX'),
    (r'^gl((Copy|Compressed)?(Multi)?Tex(ture)?Image\w*|Tex(ture)?Storage\w*|DeleteTextures\w*|Tex(ture)?Buffer\w*|'
     r'EGLImageTargetTex\w*)$', 'TEXIMAGE'),
    (r'^gl(Light\w*|ColorMaterial|(Multi)?Tex(Env|Gen)\w*|Fog[fi]v?|Fogx\w*|'
     r'BindProgramARB|ProgramStringARB|Enablei|Disablei|EnableIndexedEXT|DisableIndexedEXT)$', 'FFP'),
    (r'^gl(BindVertexArray(APPLE)?|BindBuffer(ARB)?|ClientActiveTexture(ARB)?|Delete(Buffers|VertexArrays)\w*|'
     r'PopClientAttrib)$', 'BIND'),
    (r'^gl(Draw|MultiDraw)', 'CURRENT'),
    (r'^gl', ''),
]


# Calls GL allows between glBegin and glEnd that the capture does not represent: colour
# indices, integer, double and packed attributes, half floats. Inside a captured primitive the
# driver takes the primitive over first (pl_touch_uncaptured).
UNCAPTURED = re.compile(r'^gl(Index(d|f|i|s|ub)v?|VertexAttrib[IL][1-4]\w*|VertexAttribP[1-4]uiv?|'
                        r'(Vertex|TexCoord|MultiTexCoord|Normal|Color|SecondaryColor)P[1-4]uiv?|'
                        r'(Vertex|Normal|Color|TexCoord|MultiTexCoord|FogCoord|SecondaryColor|VertexAttribs?|'
                        r'VertexWeight)[1-4]?hv?NV)$')


def mask_of(name):
    for pattern, groups in RULES:
        if re.match(pattern, name):
            if groups is None:
                return None
            bits = [GROUPS[g] for g in groups.split()]
            return ' | '.join(bits) if bits else '0'
    return '0'


# ---- the system's prototypes --------------------------------------------------------------

def parse_protos(path):
    text = open(path).read()
    text = re.sub(r'__attribute__\s*\(\([^()]*(\([^()]*\))?[^()]*\)\)', ' ', text)
    protos = {}
    for decl in text.split(';'):
        decl = ' '.join(decl.split())
        if 'typedef' in decl:
            continue
        m = re.match(r'^(?:extern )?(.+?)\b(gl[A-Z]\w*)\s*\((.*)\)$', decl)
        if not m or m.group(2) in protos:
            continue
        ret = m.group(1).strip()
        params = []
        raw = m.group(3).strip()
        if raw and raw != 'void':
            for k, p in enumerate(raw.split(',')):
                p = p.strip()
                pm = re.match(r'^(.*?)(\w+)((?:\[\d*\])*)$', p)
                if not pm or not pm.group(1).strip() or pm.group(2) in ('GLenum', 'GLint', 'GLuint'):
                    params.append((p, f'a{k}'))  # a type alone: name it
                else:
                    params.append((pm.group(1).strip() + pm.group(3), pm.group(2)))
        protos[m.group(2)] = (ret, params)
    return protos


# ---- the entry points ------------------------------------------------------------------------

entries = {}  # name -> (ret, params, body or None, kind); kind: 'hook', 'pass', 'manual', 'import'


suffix_now = ''  # appended to the names hook_entry makes (the EXT and ARB copies)


def hook_entry(name, params, hook_call):
    entries[name + suffix_now] = ('void', params, hook_call, 'hook')


def setter(base, n, t, comps, pad, norm, hook, lead=()):
    """The scalar and the v form of one attribute or vertex setter; hook(lead names, float
    expressions) gives the hook call."""
    ctype, cconv, pconv = TYPES[t]
    conv = cconv if norm else pconv
    names = comps[:n]
    lead_names = [p[1] for p in lead]
    vals = [conv.format(c) for c in names] + pad[n:]
    hook_entry(f'{base}{n}{t}', list(lead) + [(ctype, c) for c in names], hook(lead_names, vals))
    vvals = [conv.format(f'v[{i}]') for i in range(n)] + pad[n:]
    hook_entry(f'{base}{n}{t}v', list(lead) + [(f'const {ctype} *', 'v')], hook(lead_names, vvals))


def attrib_hook(attr):
    return lambda lead, vals: f'pl_hook_attrib(cx, {attr}, {", ".join(vals)})'


POS_PAD = ['0', '0', '0.0f', '1.0f']
COLOR_PAD = ['0', '0', '0', '1.0f']
TEX_PAD = ['0', '0.0f', '0.0f', '1.0f']

for n in (2, 3, 4):
    for t in ('s', 'i', 'f', 'd'):
        setter('glVertex', n, t, ['x', 'y', 'z', 'w'], POS_PAD, False,
               lambda lead, vals: f'pl_hook_vertex(cx, {", ".join(vals)})')
for n in (3, 4):
    for t in ('b', 's', 'i', 'f', 'd', 'ub', 'us', 'ui'):
        setter('glColor', n, t, ['red', 'green', 'blue', 'alpha'], COLOR_PAD, True, attrib_hook('QGL__AT_COLOR'))
for suffix_now in ('', 'EXT'):
    for t in ('b', 's', 'i', 'f', 'd', 'ub', 'us', 'ui'):
        setter('glSecondaryColor', 3, t, ['red', 'green', 'blue'], COLOR_PAD, True, attrib_hook('QGL__AT_COLOR2'))
suffix_now = ''
for t in ('b', 's', 'i', 'f', 'd'):
    setter('glNormal', 3, t, ['nx', 'ny', 'nz'], ['0', '0', '0', '0.0f'], True, attrib_hook('QGL__AT_NORMAL'))
for n in (1, 2, 3, 4):
    for t in ('s', 'i', 'f', 'd'):
        setter('glTexCoord', n, t, ['s', 't', 'r', 'q'], TEX_PAD, False,
               lambda lead, vals: f'pl_hook_texcoord(cx, 0, {", ".join(vals)})')
for suffix_now in ('', 'ARB'):
    for n in (1, 2, 3, 4):
        for t in ('s', 'i', 'f', 'd'):
            setter('glMultiTexCoord', n, t, ['s', 't', 'r', 'q'], TEX_PAD, False,
                   lambda lead, vals: f'pl_hook_texcoord(cx, {lead[0]} - GL_TEXTURE0, {", ".join(vals)})',
                   lead=[('GLenum', 'target')])
suffix_now = ''
for suffix_now in ('', 'EXT'):
    for t, ctype in (('f', 'GLfloat'), ('d', 'GLdouble')):
        fog = attrib_hook('QGL__AT_FOG')
        hook_entry(f'glFogCoord{t}', [(ctype, 'coord')], fog([], ['(float)coord', '0', '0', '0']))
        hook_entry(f'glFogCoord{t}v', [(f'const {ctype} *', 'coord')], fog([], ['(float)coord[0]', '0', '0', '0']))
suffix_now = ''
hook_entry('glEdgeFlag', [('GLboolean', 'flag')], 'pl_hook_edgeflag(cx, flag)')
hook_entry('glEdgeFlagv', [('const GLboolean *', 'flag')], 'pl_hook_edgeflag(cx, flag[0])')


# Generic attributes (glVertexAttrib*, and the ARB names): index 0 is the vertex itself.
def generic(n, t, norm, name):
    ctype, cconv, pconv = TYPES[t]
    conv = cconv if norm else pconv
    lead = [('GLuint', 'index')]
    comps = ['x', 'y', 'z', 'w']
    hook = f'pl_hook_generic(cx, index, {{}})'
    if not name.endswith('v'):
        vals = [conv.format(c) for c in comps[:n]] + POS_PAD[n:]
        hook_entry(name, lead + [(ctype, c) for c in comps[:n]], hook.format(', '.join(vals)))
    else:
        vals = [conv.format(f'v[{i}]') for i in range(n)] + POS_PAD[n:]
        hook_entry(name, lead + [(f'const {ctype} *', 'v')], hook.format(', '.join(vals)))


for suffix_now in ('', 'ARB'):
    for n in (1, 2, 3, 4):
        for t in ('s', 'f', 'd'):
            generic(n, t, False, f'glVertexAttrib{n}{t}')
            generic(n, t, False, f'glVertexAttrib{n}{t}v')
    for t in ('b', 'i', 'ub', 'us', 'ui'):
        generic(4, t, False, f'glVertexAttrib4{t}v')
    for t in ('b', 's', 'i', 'ub', 'us', 'ui'):
        generic(4, t, True, f'glVertexAttrib4N{t}v')
    ctype = TYPES['ub'][0]
    vals = [TYPES['ub'][1].format(c) for c in ('x', 'y', 'z', 'w')]
    hook_entry('glVertexAttrib4Nub', [('GLuint', 'index')] + [(ctype, c) for c in ('x', 'y', 'z', 'w')],
               f'pl_hook_generic(cx, index, {", ".join(vals)})')
suffix_now = ''

hook_entry('glMaterialf', [('GLenum', 'face'), ('GLenum', 'pname'), ('GLfloat', 'param')],
           'pl_hook_material(cx, face, pname, &param, NULL, 1)')
hook_entry('glMaterialfv', [('GLenum', 'face'), ('GLenum', 'pname'), ('const GLfloat *', 'params')],
           'pl_hook_material(cx, face, pname, params, NULL, 4)')
hook_entry('glMateriali', [('GLenum', 'face'), ('GLenum', 'pname'), ('GLint', 'param')],
           'pl_hook_material(cx, face, pname, NULL, &param, 1)')
hook_entry('glMaterialiv', [('GLenum', 'face'), ('GLenum', 'pname'), ('const GLint *', 'params')],
           'pl_hook_material(cx, face, pname, NULL, params, 4)')
hook_entry('glArrayElement', [('GLint', 'i')], 'pl_hook_array_element(cx, i)')
hook_entry('glArrayElementEXT', [('GLint', 'i')], 'pl_hook_array_element(cx, i)')

# Written by hand in C (their bodies live in capture.c, arrays.c, lists.c, eval.c, track.c).
MANUAL = ['glBegin', 'glEnd', 'glNewList', 'glEndList', 'glCallList', 'glCallLists', 'glDeleteLists', 'glListBase',
          'glDrawArrays', 'glDrawArraysEXT', 'glDrawElements', 'glDrawRangeElements', 'glDrawRangeElementsEXT',
          'glMultiDrawArrays', 'glMultiDrawArraysEXT', 'glMultiDrawElements', 'glMultiDrawElementsEXT',
          'glEvalMesh2', 'glEvalCoord1f', 'glEvalCoord1d', 'glEvalCoord1fv', 'glEvalCoord1dv', 'glEvalCoord2f',
          'glEvalCoord2d', 'glEvalCoord2fv', 'glEvalCoord2dv', 'glEvalPoint1', 'glEvalPoint2',
          'glEnable', 'glDisable']


def proto(params):
    return ', '.join(t if n is None else (f'{t}{n}' if t.endswith('*') else f'{t} {n}')
                     for t, n in params) or 'void'


def proto_decl(params):
    out = []
    for t, n in params:
        m = re.match(r'^(.*?)((?:\[\d*\])+)$', t)
        if m:  # an array parameter: the name goes before the brackets
            out.append(f'{m.group(1)} {n}{m.group(2)}')
        else:
            out.append(f'{t}{n}' if t.endswith('*') else f'{t} {n}')
    return ', '.join(out) or 'void'


def args(params):
    return ', '.join(n for _, n in params)


def zero(ret):
    return '' if ret == 'void' else ' 0'


def main():
    protos = parse_protos(sys.argv[1])
    out_h, out_c = sys.argv[2], sys.argv[3]
    # The system's signature wins for the names it declares (its parameter types are exact).
    for name in list(entries):
        if name in protos and entries[name][3] == 'hook':
            ret, params = protos[name]
            if len(params) != len(entries[name][1]):
                sys.exit(f'gen_entries.py: {name} has {len(params)} parameters in the headers')
            entries[name] = (ret, [(t, n) for (t, _), (_, n) in zip(params, entries[name][1])],
                             entries[name][2], 'hook')
    for name in MANUAL:
        if name not in protos:
            sys.exit(f'gen_entries.py: the headers do not declare {name}')
        ret, params = protos[name]
        entries[name] = (ret, params, None, 'manual')
    for name, (ret, params) in protos.items():
        if name not in entries:
            entries[name] = (ret, params, None, 'pass')
    names = sorted(entries)

    h = ['/* Generated by gen_entries.py: the real-driver slots of the preload library. */',
         '#ifndef PL_ENTRIES_H', '#define PL_ENTRIES_H', '', 'enum pl_slot {']
    h += [f'    PL_{name},' for name in names]
    h += ['    PL_SLOT_COUNT', '};', '']
    for name in names:
        ret, params, _, _ = entries[name]
        h.append(f'typedef {ret} (*PFN_pl_{name})({proto_decl([(t, "") for t, _ in params]) if params else "void"});')
    h += ['', 'extern void *pl_real_slot[PL_SLOT_COUNT];',
          'extern void *const pl_none_slot[PL_SLOT_COUNT];',
          'extern const char *const pl_slot_name[PL_SLOT_COUNT];',
          '/* The real driver function of a slot (resolved on first call). */',
          '#define REAL(name) ((PFN_pl_##name)pl_real_slot[PL_##name])',
          '', '#endif', '']

    c = ['/* Generated by gen_entries.py: lazy real-driver slots, exported wrappers and the name',
         ' * table of the preload library. Do not edit. */',
         '#include "preload.h"', '',
         '#pragma GCC diagnostic ignored "-Wunused-parameter"', '']
    c.append('const char *const pl_slot_name[PL_SLOT_COUNT] = {')
    c += [f'    "{name}",' for name in names]
    c += ['};', '']
    for name in names:
        ret, params, _, _ = entries[name]
        ret_kw = '' if ret == 'void' else 'return '
        c += [f'static {ret} pl_lazy_{name}({proto_decl(params)})', '{',
              f'    pl_resolve_slot(PL_{name});', f'    {ret_kw}REAL({name})({args(params)});', '}']
        c += [f'static {ret} pl_none_{name}({proto_decl(params)})', '{', f'    return{zero(ret)};', '}']
    c += ['', 'void *const pl_none_slot[PL_SLOT_COUNT] = {']
    c += [f'    (void *)pl_none_{name},' for name in names]
    c += ['};', '', 'void *pl_real_slot[PL_SLOT_COUNT] = {']
    c += [f'    (void *)pl_lazy_{name},' for name in names]
    c += ['};', '']
    for name in names:
        ret, params, body, kind = entries[name]
        if kind == 'manual':
            continue
        ret_kw = '' if ret == 'void' else 'return '
        c.append(f'PL_EXPORT {ret} {name}({proto_decl(params)})')
        c.append('{')
        if kind == 'hook':
            c.append('    pl_ctx *cx = pl_tls_ctx;')
            c.append(f'    if (PL_UNLIKELY(cx != NULL) && {body})')
            c.append('        return;')
        elif UNCAPTURED.match(name):
            c.append('    pl_touch_uncaptured();')
        else:
            mask = mask_of(name)
            if mask is None:
                c.append('    if (PL_UNLIKELY(pl_inside_capture()))')
            else:
                c.append(f'    if (PL_UNLIKELY(pl_touch({mask})))')
            c.append(f'        return{zero(ret)};')
        c.append(f'    {ret_kw}REAL({name})({args(params)});')
        c.append('}')
        c.append('')
    c.append('const pl_proc pl_proc_table[] = {')
    c += [f'    {{"{name}", (void *){name}}},' for name in names]
    c += ['};', f'const int pl_proc_count = {len(names)};', '']
    with open(out_h, 'w') as f:
        f.write('\n'.join(h))
    with open(out_c, 'w') as f:
        f.write('\n'.join(c))


main()
