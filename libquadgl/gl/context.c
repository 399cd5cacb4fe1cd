/* context.c: the qgl_context's life cycle, options, counters and the per-thread current one.
 *
 * A context is created inside the application's current GL context. It resolves the GL entry
 * points, reads what the driver offers (version, profile, geometry shaders, vertex array
 * objects, the quads' provoking vertex rule) and creates its own vertex array object and
 * buffers. Only when a quad first needs smoothing (qgl__ready) does it compile a first program
 * to prove the shader path works (the geometry shader path on GL 3.2, else the GLSL 1.20 one
 * of glsl120.c; when neither compiles the context keeps working on the CPU fallback alone) and
 * measure the driver's costs for the planner (calibrate.c): a compile costs the driver
 * megabytes, which a program whose quads all split never needs. Options come from the desc,
 * then from the environment (QUADGL_METHOD, QUADGL_TOLERANCE), then from defaults. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

/* initial-exec: one load per immediate-mode call instead of a __tls_get_addr call. */
__attribute__((tls_model("initial-exec"))) _Thread_local qgl_context *qgl__tls_current;

qgl_context *qgl__current(void)
{
    return qgl__tls_current;
}

QGL_API void qgl_gl_make_current(qgl_context *ctx)
{
    qgl__tls_current = ctx;
}

QGL_API qgl_context *qgl_gl_current(void)
{
    return qgl__tls_current;
}

static qgl_method env_method(void)
{
    static const struct {
        const char *name;
        qgl_method method;
    } names[] = {{"mvc", QGL_METHOD_MVC}, {"mvcplane", QGL_METHOD_MVC_PLANE}, {"split", QGL_METHOD_SPLIT},
                 {"subdiv", QGL_METHOD_SUBDIV}};
    const char *s = secure_getenv("QUADGL_METHOD");
    for (size_t i = 0; s && i < sizeof names / sizeof names[0]; i++)
        if (!strcmp(s, names[i].name))
            return names[i].method;
    return QGL_METHOD_AUTO;
}

static float env_float(const char *name, float def)
{
    const char *s = secure_getenv(name);
    char *end;
    float v = s ? strtof(s, &end) : 0;
    return s && end != s && v > 0 ? v : def;
}

int qgl__has_extension(qgl_context *ctx, const char *name)
{
    struct qgl__gl *gl = &ctx->gl;
    int major = ctx->version / 10;
    if (major >= 3 && gl->GetStringi) {
        GLint n = 0;
        gl->GetIntegerv(GL_NUM_EXTENSIONS, &n);
        for (GLint i = 0; i < n; i++) {
            const char *e = (const char *)gl->GetStringi(GL_EXTENSIONS, (GLuint)i);
            if (e && !strcmp(e, name))
                return 1;
        }
        return 0;
    }
    const char *all = (const char *)gl->GetString(GL_EXTENSIONS);
    size_t len = strlen(name);
    for (const char *p = all; p && (p = strstr(p, name)); p += len)
        if ((p == all || p[-1] == ' ') && (p[len] == ' ' || p[len] == 0))
            return 1;
    return 0;
}

/* Our own vertex array object: drawing through it leaves the application's vertex array
 * state alone (only the bindings need restoring). Its arrays point into the stream buffer. */
static void create_objects(qgl_context *ctx)
{
    ctx->gl.GenVertexArrays(1, &ctx->vao);
    qgl__stream_init(ctx);
}

/* Returns whether the GLSL 1.20 path may serve (GL 2.0 compatibility, GLSL 1.20, allowed). */
static int probe_driver(qgl_context *ctx, const qgl_gl_desc *d)
{
    struct qgl__gl *gl = &ctx->gl;
    const char *ver = (const char *)gl->GetString(GL_VERSION);
    int major = 1, minor = 0;
    if (ver)
        sscanf(ver, "%d.%d", &major, &minor);
    int v = major * 10 + minor;
    ctx->version = v;
    GLint profile = 0;
    if (v >= 32)
        gl->GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    int compat = v < 32 || (profile & GL_CONTEXT_COMPATIBILITY_PROFILE_BIT);
    ctx->has_vao = v >= 30 && gl->GenVertexArrays && gl->BindVertexArray && gl->GenBuffers &&
                   gl->BufferData && gl->SecondaryColorPointer && gl->FogCoordPointer;
    if (v >= 32) {
        GLboolean follow = GL_FALSE;
        gl->GetBooleanv(GL_QUADS_FOLLOW_PROVOKING_VERTEX_CONVENTION, &follow);
        ctx->quads_follow_pv = follow;
    }
    ctx->has_arb_vp = qgl__has_extension(ctx, "GL_ARB_vertex_program");
    ctx->has_arb_fp = qgl__has_extension(ctx, "GL_ARB_fragment_program");
    ctx->has_ati_fs = qgl__has_extension(ctx, "GL_ATI_fragment_shader");
    ctx->has_pipelines = v >= 41 || qgl__has_extension(ctx, "GL_ARB_separate_shader_objects");
    gl->GetIntegerv(GL_MAX_TEXTURE_UNITS, &ctx->max_units);
    gl->GetIntegerv(GL_MAX_CLIP_PLANES, &ctx->max_clip_planes);
    int cap = d->max_glsl ? d->max_glsl : 1000;
    ctx->shader_level = (v >= 32 && compat && ctx->has_vao && gl->CreateShader && cap >= 150 &&
                         !d->force_fallback) ? 150 : 0;
    return compat && cap >= 120 && !d->force_fallback && qgl__glsl120_supported(ctx);
}

/* The best shader path that compiles here: geometry shaders, else GLSL 1.20, else none. */
static void choose_shader_path(qgl_context *ctx)
{
    if (ctx->shader_level == 150 && !qgl__program(ctx, 0))
        ctx->shader_level = ctx->glsl120_ok ? 120 : 0;
    if (ctx->shader_level == 120 && !qgl__glsl120_init(ctx))
        ctx->shader_level = 0;
}

QGL_API qgl_context *qgl_gl_create(const qgl_gl_desc *desc)
{
    qgl_gl_desc d = desc ? *desc : (qgl_gl_desc){0};
    qgl_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return NULL;
    if (!qgl__gl_load(&ctx->gl, d.get_proc) || !ctx->gl.GetString(GL_VERSION)) {
        free(ctx);
        return NULL;
    }
    ctx->method = d.method ? d.method : env_method();
    ctx->tolerance_px = d.tolerance_px > 0 ? d.tolerance_px : env_float("QUADGL_TOLERANCE", 0.5f);
    ctx->invisible_area_px = d.invisible_area_px > 0 ? d.invisible_area_px : 4.0f;
    ctx->split_error = d.split_error;
    const char *se = secure_getenv("QUADGL_SPLIT_ERROR"); /* a scale; negative turns the rule off */
    char *end;
    float se_value = se ? strtof(se, &end) : 0;
    if (!d.split_error && se && end != se && se_value != 0)
        ctx->split_error = se_value;
    ctx->exclusive = d.assume_exclusive != 0;
    ctx->glsl120_ok = probe_driver(ctx, &d);
    if (!ctx->shader_level && ctx->glsl120_ok)
        ctx->shader_level = 120;
    qgl__costs_given(ctx);
    if (ctx->has_vao)
        create_objects(ctx);
    return ctx;
}

int qgl__ready(qgl_context *ctx)
{
    int level = ctx->shader_level;
    if (ctx->ready)
        return 0;
    ctx->ready = 1;
    qgl_gl_stats_t before = ctx->stats;
    choose_shader_path(ctx);
    qgl__calibrate(ctx);
    ctx->stats = before; /* the calibration's draws are not the program's */
    return level != ctx->shader_level;
}

QGL_API void qgl_gl_destroy(qgl_context *ctx)
{
    if (!ctx)
        return;
    if (!ctx->gl_gone)
        qgl__flush(ctx); /* inside its GL context, as the owner destroys it */
    if (qgl__tls_current == ctx)
        qgl__tls_current = NULL;
    qgl__programs_free(ctx);
    qgl__glsl120_free(ctx);
    qgl__grid_free(ctx);
    free(ctx->arrays);
    if (ctx->has_vao) {
        if (!ctx->gl_gone)
            ctx->gl.DeleteVertexArrays(1, &ctx->vao);
        qgl__stream_free(ctx);
    }
    qgl__verts_free(&ctx->cap);
    qgl__verts_free(&ctx->sub);
    qgl__verts_free(&ctx->pvmat);
    qgl__verts_free(&ctx->unrolled);
    qgl__verts_free(&ctx->grouped);
    free(ctx->grouped_clip);
    free(ctx->grouped_to);
    free(ctx->unrolled_facts);
    qgl__verts_free(&ctx->pend);
    free(ctx->multi_first);
    free(ctx->multi_offset);
    free(ctx->ways);
    free(ctx->multi_count);
    free(ctx->clip);
    free(ctx->path);
    free(ctx);
}

void qgl__gl_forget(qgl_context *ctx)
{
    if (!ctx)
        return;
    ctx->gl_gone = 1;
    qgl_gl_destroy(ctx);
}

QGL_API void qgl_gl_set_method(qgl_context *ctx, qgl_method method)
{
    if (ctx && method >= QGL_METHOD_AUTO && method <= QGL_METHOD_MVC_PLANE) {
        qgl__flush(ctx); /* waiting quads were given under the old method */
        ctx->method = method;
    }
}

QGL_API qgl_method qgl_gl_get_method(const qgl_context *ctx)
{
    return ctx ? ctx->method : QGL_METHOD_AUTO;
}

QGL_API int qgl_gl_shader_level(const qgl_context *ctx)
{
    if (ctx)
        qgl__ready((qgl_context *)ctx); /* the level a program compiled at, not the promised one */
    return ctx ? ctx->shader_level : 0;
}

QGL_API void qgl_gl_stats(const qgl_context *ctx, qgl_gl_stats_t *out)
{
    if (ctx && out)
        *out = ctx->stats;
}

QGL_API void qgl_gl_reset_stats(qgl_context *ctx)
{
    if (ctx)
        memset(&ctx->stats, 0, sizeof ctx->stats);
}

/* ---- vertex arrays ------------------------------------------------------------------------ */

static int grow(void **p, size_t n, size_t elem)
{
    void *q = realloc(*p, n * elem);
    if (!q)
        return 0;
    *p = q;
    return 1;
}

/* Room for n vertices of position and every attribute in need. When the capacity grows every
 * allocated array grows with it, so arrays stay interchangeable. Does not touch v->mask. */
int qgl__verts_reserve(qgl__verts *v, size_t n, unsigned need)
{
    if (n <= v->cap && (need & ~v->alloc) == 0 && v->pos)
        return 1;
    size_t cap = v->cap;
    if (n > cap)
        cap = n > 2 * cap ? n : 2 * cap;
    if (cap < 256)
        cap = 256;
    unsigned all = need | v->alloc;
    int ok = grow((void **)&v->pos, cap, 4 * sizeof(float));
    for (int a = 0; a < QGL__NATTR; a++)
        ok = ok && (!(all & (1u << a)) || grow((void **)&v->attr[a], cap, (size_t)qgl__attribs[a].floats * sizeof(float)));
    ok = ok && (!(all & QGL__A_EDGE) || grow((void **)&v->edge, cap, 1));
    ok = ok && (!(all & QGL__A_MATERIAL) || grow((void **)&v->mat, cap, QGL__MATERIAL_FLOATS * sizeof(float)));
    if (!ok)
        return 0;
    v->cap = cap;
    v->alloc = all;
    return 1;
}

void qgl__verts_copy(qgl__verts *d, size_t i, const qgl__verts *s, size_t j)
{
    unsigned m = s->mask;
    memcpy(d->pos + 4 * i, s->pos + 4 * j, 4 * sizeof(float));
    for (int a = 0; a < QGL__NATTR; a++)
        if (m & (1u << a)) {
            size_t k = (size_t)qgl__attribs[a].floats;
            memcpy(d->attr[a] + k * i, s->attr[a] + k * j, k * sizeof(float));
        }
    if (m & QGL__A_EDGE)
        d->edge[i] = s->edge[j];
    if (m & QGL__A_MATERIAL)
        memcpy(d->mat + QGL__MATERIAL_FLOATS * i, s->mat + QGL__MATERIAL_FLOATS * j,
               QGL__MATERIAL_FLOATS * sizeof(float));
}

void qgl__verts_copy_range(qgl__verts *d, size_t i, const qgl__verts *s, size_t j, size_t n)
{
    unsigned m = s->mask;
    memcpy(d->pos + 4 * i, s->pos + 4 * j, 4 * n * sizeof(float));
    for (int a = 0; a < QGL__NATTR; a++)
        if (m & (1u << a)) {
            size_t k = (size_t)qgl__attribs[a].floats;
            memcpy(d->attr[a] + k * i, s->attr[a] + k * j, k * n * sizeof(float));
        }
    if (m & QGL__A_EDGE)
        memcpy(d->edge + i, s->edge + j, n);
    if (m & QGL__A_MATERIAL)
        memcpy(d->mat + QGL__MATERIAL_FLOATS * i, s->mat + QGL__MATERIAL_FLOATS * j,
               QGL__MATERIAL_FLOATS * n * sizeof(float));
}

/* Strip quads' corners into quads, k floats per vertex (sizes as constants: inlined copies). */
static void unroll_floats(float *d, const float *s, size_t k, size_t nq, const int from[4])
{
    for (size_t q = 0; q < nq; q++, d += 4 * k, s += 2 * k)
        for (int c = 0; c < 4; c++) {
            const float *f = s + (size_t)from[c] * k;
            float *t = d + (size_t)c * k;
            switch (k) {
            case 1: t[0] = f[0]; break;
            case 3: memcpy(t, f, 3 * sizeof(float)); break;
            case 4: memcpy(t, f, 4 * sizeof(float)); break;
            default: memcpy(t, f, k * sizeof(float));
            }
        }
}

void qgl__verts_unroll(qgl__verts *d, size_t i, const qgl__verts *s, size_t j, size_t nq, int shift)
{
    static const int strip[4] = {0, 1, 3, 2};
    int from[4];
    for (int c = 0; c < 4; c++)
        from[c] = strip[(c + shift) & 3];
    unsigned m = s->mask;
    unroll_floats(d->pos + 4 * i, s->pos + 4 * j, 4, nq, from);
    for (int a = 0; a < QGL__NATTR; a++)
        if (m & (1u << a)) {
            size_t k = (size_t)qgl__attribs[a].floats;
            unroll_floats(d->attr[a] + k * i, s->attr[a] + k * j, k, nq, from);
        }
    if (m & QGL__A_MATERIAL)
        unroll_floats(d->mat + QGL__MATERIAL_FLOATS * i, s->mat + QGL__MATERIAL_FLOATS * j, QGL__MATERIAL_FLOATS, nq,
                      from);
    if (m & QGL__A_EDGE)
        for (size_t q = 0; q < nq; q++)
            for (int c = 0; c < 4; c++)
                d->edge[i + 4 * q + (size_t)c] = s->edge[j + 2 * q + (size_t)from[c]];
}

void qgl__verts_free(qgl__verts *v)
{
    free(v->pos);
    for (int a = 0; a < QGL__NATTR; a++)
        free(v->attr[a]);
    free(v->edge);
    free(v->mat);
    memset(v, 0, sizeof *v);
}
