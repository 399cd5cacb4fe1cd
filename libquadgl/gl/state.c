/* state.c: read the application's GL state at a draw and reduce it to the program key.
 *
 * Everything that decides how a quad may be drawn is read here, once per batch: matrices,
 * viewport, shade model, render and polygon modes, whether drawing order can show (depth,
 * blending, stencil, logic op), and the fixed-function features the
 * generated programs reproduce (lighting with its lights' kinds, colour material, light model,
 * normal scaling, every texture unit's target, texgen modes, environment with its COMBINE
 * state and the texture's base format, fog, colour sum, clip planes). The result is the key
 * of shader.c, with every field that cannot change the picture left zero so that equal
 * pictures share a program. A state the programs do not reproduce (an env mode or COMBINE
 * source outside GL 1.4's, a depth texture, units past QGL_MAX_TEXUNITS, too many varyings)
 * clears "modelled" and its quads take the CPU fallback, which draws through the driver's
 * fixed function; the application's own programs (a GLSL program or pipeline, ARB vertex or
 * fragment programs, an ATI fragment shader) replace fixed function, so their quads go to the
 * driver as they are ("own_pipeline").
 * The planner also learns whether the per-vertex results are affine in the captured
 * attributes (unlit or flat, linear texgen only): only then can the diagonal split be exact.
 * Parameters (light colours, planes, fog distances...) are not read: the programs take them
 * from the built-in uniforms, which the driver keeps current. Queries never raise a GL error
 * (only enums of the context's version are asked) and the active texture unit is put back. */
#include <math.h>
#include <string.h>

#include "gl_internal.h"

static void mat_mul(const double a[16], const double b[16], double r[16])
{
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
}

/* Texture targets in fixed function's priority order (cube map first), with the GL version
 * that has them: querying an unknown one is an error the application would see. */
static const struct { GLenum target, binding; int version; uint8_t code; } tex_targets[] = {
    {GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BINDING_CUBE_MAP, 13, QGL__T_CUBE},
    {GL_TEXTURE_3D, GL_TEXTURE_BINDING_3D, 12, QGL__T_3D},
    {GL_TEXTURE_RECTANGLE, GL_TEXTURE_BINDING_RECTANGLE, 31, QGL__T_RECT},
    {GL_TEXTURE_2D, GL_TEXTURE_BINDING_2D, 10, QGL__T_2D},
    {GL_TEXTURE_1D, GL_TEXTURE_BINDING_1D, 10, QGL__T_1D}};
#define NTARGETS (sizeof tex_targets / sizeof tex_targets[0])

/* The enabled target of the active unit with the highest priority: its tex_targets index, or
 * -1 for none. */
static int unit_target(qgl_context *ctx)
{
    for (size_t t = 0; t < NTARGETS; t++)
        if (ctx->version >= tex_targets[t].version && ctx->gl.IsEnabled(tex_targets[t].target))
            return (int)t;
    return -1;
}

static int target_index(uint8_t code)
{
    for (size_t t = 0; t < NTARGETS; t++)
        if (tex_targets[t].code == code)
            return (int)t;
    return -1;
}

/* Base-format class of the bound texture's level 0; 0 for a depth texture (compared, or
 * read as luminance/intensity/alpha by a mode we do not model). */
static int base_format(qgl_context *ctx, GLenum target, uint8_t *fmt)
{
    struct qgl__gl *gl = &ctx->gl;
    GLenum level_target = target == GL_TEXTURE_CUBE_MAP ? GL_TEXTURE_CUBE_MAP_POSITIVE_X : target;
    GLint alpha = 0, red = 0, lum = 0, inten = 0, depth = 0;
    gl->GetTexLevelParameteriv(level_target, 0, GL_TEXTURE_ALPHA_SIZE, &alpha);
    gl->GetTexLevelParameteriv(level_target, 0, GL_TEXTURE_RED_SIZE, &red);
    gl->GetTexLevelParameteriv(level_target, 0, GL_TEXTURE_LUMINANCE_SIZE, &lum);
    gl->GetTexLevelParameteriv(level_target, 0, GL_TEXTURE_INTENSITY_SIZE, &inten);
    if (ctx->version >= 14)
        gl->GetTexLevelParameteriv(level_target, 0, GL_TEXTURE_DEPTH_SIZE, &depth);
    if (depth > 0)
        return 0;
    if (inten > 0)
        *fmt = QGL__F_INTENSITY;
    else if (alpha > 0 && red == 0 && lum == 0)
        *fmt = QGL__F_ALPHA;
    else
        *fmt = alpha > 0 ? QGL__F_RGBA : QGL__F_RGB;
    return 1;
}

static int find(const GLint *list, int n, GLint value)
{
    for (int i = 0; i < n; i++)
        if (list[i] == value)
            return i;
    return -1;
}

static int combine_func(GLint f, int rgb)
{
    static const GLint funcs[] = {GL_REPLACE, GL_MODULATE, GL_ADD, GL_ADD_SIGNED, GL_INTERPOLATE,
                                  GL_SUBTRACT, GL_DOT3_RGB, GL_DOT3_RGBA};
    return find(funcs, rgb ? 8 : 6, f);
}

static int combine_source(GLint s, int max_units)
{
    static const GLint srcs[] = {GL_TEXTURE, GL_CONSTANT, GL_PRIMARY_COLOR, GL_PREVIOUS};
    int i = find(srcs, 4, s);
    if (i >= 0)
        return i;
    if (s >= GL_TEXTURE0 && s < GL_TEXTURE0 + max_units && s < GL_TEXTURE0 + QGL_MAX_TEXUNITS)
        return QGL__S_UNIT0 + (s - GL_TEXTURE0);
    return -1;
}

static int scale_shift(GLint s)
{
    return s == 1 ? 0 : s == 2 ? 1 : s == 4 ? 2 : -1;
}

/* COMBINE state of the active unit; only the arguments its functions read. */
static int query_combine(qgl_context *ctx, qgl__unit_key *uk)
{
    struct qgl__gl *gl = &ctx->gl;
    static const GLint ops[] = {GL_SRC_COLOR, GL_ONE_MINUS_SRC_COLOR, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA};
    GLint frgb = 0, fa = 0, srgb = 1, sa = 1;
    gl->GetTexEnviv(GL_TEXTURE_ENV, GL_COMBINE_RGB, &frgb);
    gl->GetTexEnviv(GL_TEXTURE_ENV, GL_COMBINE_ALPHA, &fa);
    gl->GetTexEnviv(GL_TEXTURE_ENV, GL_RGB_SCALE, &srgb);
    gl->GetTexEnviv(GL_TEXTURE_ENV, GL_ALPHA_SCALE, &sa);
    int f0 = combine_func(frgb, 1), f1 = combine_func(fa, 0), s0 = scale_shift(srgb), s1 = scale_shift(sa);
    if (f0 < 0 || f1 < 0 || s0 < 0 || s1 < 0)
        return 0;
    int dot4 = f0 == QGL__C_DOT3_RGBA;
    uk->func_rgb = (uint8_t)f0;
    uk->func_a = dot4 ? 0 : (uint8_t)f1;
    uk->shift_rgb = (uint8_t)s0;
    uk->shift_a = dot4 ? 0 : (uint8_t)s1;
    int nrgb = f0 == QGL__C_REPLACE ? 1 : f0 == QGL__C_INTERPOLATE ? 3 : 2;
    int na = dot4 ? 0 : f1 == QGL__C_REPLACE ? 1 : f1 == QGL__C_INTERPOLATE ? 3 : 2;
    for (int i = 0; i < 3; i++) {
        GLint s = 0, o = 0;
        if (i < nrgb) {
            gl->GetTexEnviv(GL_TEXTURE_ENV, GL_SRC0_RGB + i, &s);
            gl->GetTexEnviv(GL_TEXTURE_ENV, GL_OPERAND0_RGB + i, &o);
            int src = combine_source(s, ctx->max_units), op = find(ops, 4, o);
            if (src < 0 || op < 0)
                return 0;
            uk->src_rgb[i] = (uint8_t)src, uk->op_rgb[i] = (uint8_t)op;
        }
        if (i < na) {
            gl->GetTexEnviv(GL_TEXTURE_ENV, GL_SRC0_ALPHA + i, &s);
            gl->GetTexEnviv(GL_TEXTURE_ENV, GL_OPERAND0_ALPHA + i, &o);
            int src = combine_source(s, ctx->max_units), op = find(ops + 2, 2, o);
            if (src < 0 || op < 0)
                return 0;
            uk->src_a[i] = (uint8_t)src, uk->op_a[i] = (uint8_t)(op + 2);
        }
    }
    return 1;
}

static int query_texgen(qgl_context *ctx, qgl__unit_key *uk)
{
    struct qgl__gl *gl = &ctx->gl;
    static const GLenum coords[4] = {GL_S, GL_T, GL_R, GL_Q};
    static const GLint modes[] = {0, GL_OBJECT_LINEAR, GL_EYE_LINEAR, GL_SPHERE_MAP, GL_REFLECTION_MAP, GL_NORMAL_MAP};
    for (int c = 0; c < 4; c++) {
        if (!gl->IsEnabled(GL_TEXTURE_GEN_S + (GLenum)c))
            continue;
        GLint mode = 0;
        gl->GetTexGeniv(coords[c], GL_TEXTURE_GEN_MODE, &mode);
        int m = find(modes, ctx->version >= 13 ? 6 : 4, mode);
        if (m <= 0 || (m == QGL__G_SPHERE && c >= 2))
            return 0;
        uk->gen[c] = (uint8_t)m;
    }
    return 1;
}

/* Level 0's size in texels per coordinate (what a coordinate error of 1 is in texels); a
 * rectangle texture's coordinates are texels already. */
static void texture_size(qgl_context *ctx, GLenum target, float size[3])
{
    static const GLenum dims[3] = {GL_TEXTURE_WIDTH, GL_TEXTURE_HEIGHT, GL_TEXTURE_DEPTH};
    GLenum level_target = target == GL_TEXTURE_CUBE_MAP ? GL_TEXTURE_CUBE_MAP_POSITIVE_X : target;
    for (int d = 0; d < 3; d++) {
        GLint n = 1;
        if (target != GL_TEXTURE_RECTANGLE && (d < 2 || target == GL_TEXTURE_3D))
            ctx->gl.GetTexLevelParameteriv(level_target, 0, dims[d], &n);
        size[d] = n > 1 ? (float)n : 1.0f;
    }
}

/* The level 0 facts of the texture bound to target t of the active unit: kept by name until
 * the owner marks an image change (QGL__D_TEXIMAGE empties them). */
static const qgl__texfacts *texture_facts(qgl_context *ctx, int t)
{
    GLint name = 0;
    ctx->gl.GetIntegerv(tex_targets[t].binding, &name);
    qgl__texfacts *f = &ctx->tex_facts[(GLuint)name % QGL__TEX_FACTS];
    if (f->used && f->name == (GLuint)name && f->target == tex_targets[t].code)
        return f;
    f->used = 1, f->name = (GLuint)name, f->target = tex_targets[t].code;
    f->ok = (uint8_t)base_format(ctx, tex_targets[t].target, &f->format);
    texture_size(ctx, tex_targets[t].target, f->size);
    return f;
}

/* The active unit u (target t already known): env, format, texgen, matrix. */
static int query_unit(qgl_context *ctx, qgl__state *st, int u, int t, qgl__unit_key *uk)
{
    struct qgl__gl *gl = &ctx->gl;
    static const GLint envs[] = {GL_MODULATE, GL_REPLACE, GL_DECAL, GL_BLEND, GL_ADD, GL_COMBINE};
    GLint env = GL_MODULATE;
    gl->GetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &env);
    int e = find(envs, 6, env);
    if (e < 0)
        return 0;
    uk->env = (uint8_t)e;
    if (e == QGL__E_COMBINE && !query_combine(ctx, uk))
        return 0;
    const qgl__texfacts *f = texture_facts(ctx, t);
    if (!f->ok)
        return 0;
    if (e != QGL__E_COMBINE)
        uk->format = f->format;
    memcpy(st->texsize[u], f->size, sizeof f->size);
    return query_texgen(ctx, uk);
}

/* Every unit; 0 when one is beyond what the programs reproduce. */
static int query_textures(qgl_context *ctx, qgl__state *st, qgl__key *k)
{
    struct qgl__gl *gl = &ctx->gl;
    int ok = 1;
    for (GLint u = 0; u < ctx->max_units; u++) {
        if (u > 0 || st->active_texture != GL_TEXTURE0)
            gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        int t = unit_target(ctx);
        if (t < 0)
            continue;
        if (u >= QGL_MAX_TEXUNITS) {
            ok = 0;
            continue;
        }
        k->unit[u].target = tex_targets[t].code;
        k->nunits = (uint8_t)(u + 1);
        ok &= query_unit(ctx, st, u, t, &k->unit[u]);
    }
    if (ctx->max_units > 1 || st->active_texture != GL_TEXTURE0)
        gl->ActiveTexture((GLenum)st->active_texture);
    /* a COMBINE argument reading another unit needs that unit enabled */
    for (int u = 0; u < k->nunits; u++)
        for (int i = 0; i < 3; i++) {
            int s = k->unit[u].src_rgb[i] > k->unit[u].src_a[i] ? k->unit[u].src_rgb[i] : k->unit[u].src_a[i];
            if (s >= QGL__S_UNIT0 && !k->unit[s - QGL__S_UNIT0].target)
                ok = 0;
        }
    return ok;
}

static void query_lighting(qgl_context *ctx, qgl__key *k)
{
    struct qgl__gl *gl = &ctx->gl;
    k->flags |= QGL__KF_LIGHTING;
    for (int i = 0; i < 8; i++) {
        if (!gl->IsEnabled(GL_LIGHT0 + (GLenum)i))
            continue;
        GLfloat pos[4] = {0}, cutoff = 180;
        gl->GetLightfv(GL_LIGHT0 + (GLenum)i, GL_POSITION, pos);
        gl->GetLightfv(GL_LIGHT0 + (GLenum)i, GL_SPOT_CUTOFF, &cutoff);
        k->lights |= (uint8_t)(1u << i);
        if (pos[3] != 0)
            k->light_pos |= (uint8_t)(1u << i);
        if (pos[3] != 0 && cutoff != 180) /* directional lights ignore spot parameters */
            k->light_spot |= (uint8_t)(1u << i);
    }
    GLint two = 0, local = 0, control = GL_SINGLE_COLOR;
    gl->GetIntegerv(GL_LIGHT_MODEL_TWO_SIDE, &two);
    gl->GetIntegerv(GL_LIGHT_MODEL_LOCAL_VIEWER, &local);
    if (ctx->version >= 12)
        gl->GetIntegerv(GL_LIGHT_MODEL_COLOR_CONTROL, &control);
    k->flags |= (two ? QGL__KF_TWO_SIDE : 0) | (local ? QGL__KF_LOCAL_VIEWER : 0) |
                (control == GL_SEPARATE_SPECULAR_COLOR ? QGL__KF_SEPARATE_SPEC : 0);
    if (gl->IsEnabled(GL_COLOR_MATERIAL)) {
        static const GLint faces[] = {0, GL_FRONT, GL_BACK, GL_FRONT_AND_BACK};
        static const GLint modes[] = {0, GL_EMISSION, GL_AMBIENT, GL_DIFFUSE, GL_SPECULAR, GL_AMBIENT_AND_DIFFUSE};
        GLint face = GL_FRONT_AND_BACK, mode = GL_AMBIENT_AND_DIFFUSE;
        gl->GetIntegerv(GL_COLOR_MATERIAL_FACE, &face);
        gl->GetIntegerv(GL_COLOR_MATERIAL_PARAMETER, &mode);
        int f = find(faces, 4, face), m = find(modes, 6, mode);
        k->cm_face = (uint8_t)(f > 0 ? f : 0);
        k->cm_mode = (uint8_t)(m > 0 && f > 0 ? m : 0);
        if (!two) /* the back material is never used */
            k->cm_face &= 1;
        if (!k->cm_face)
            k->cm_mode = 0;
    }
}

static void query_fog(qgl_context *ctx, qgl__key *k)
{
    struct qgl__gl *gl = &ctx->gl;
    static const GLint modes[] = {0, GL_LINEAR, GL_EXP, GL_EXP2};
    GLint mode = GL_EXP, src = GL_FRAGMENT_DEPTH;
    gl->GetIntegerv(GL_FOG_MODE, &mode);
    if (ctx->version >= 14)
        gl->GetIntegerv(GL_FOG_COORD_SRC, &src);
    int m = find(modes, 4, mode);
    k->fog = (uint8_t)(m > 0 ? m : QGL__FOG_EXP);
    if (src != GL_FOG_COORD)
        k->flags |= QGL__KF_FOG_DEPTH;
}

/* Steepest slope of the fog factor in the fog coordinate c (c >= 0): linear
 * (end - c) / (end - start) has 1 / |end - start|; exp(-d c) at most d; exp(-(d c)^2) at most
 * d sqrt(2 / e) (its inflection point). The factor's change bounds the colour's. */
static double fog_slope(qgl_context *ctx, const qgl__key *k)
{
    float start = 0, end = 1, density = 1;
    if (k->fog == QGL__FOG_LINEAR) {
        ctx->gl.GetFloatv(GL_FOG_START, &start);
        ctx->gl.GetFloatv(GL_FOG_END, &end);
        return end != start ? 1.0 / fabs((double)end - start) : INFINITY;
    }
    ctx->gl.GetFloatv(GL_FOG_DENSITY, &density);
    return fabs((double)density) * (k->fog == QGL__FOG_EXP2 ? 0.8578 : 1.0);
}

/* Some unit generates coordinates from the normal (sphere, reflection or normal map): not
 * affine in the position, and a reader of the normal. */
static int normal_texgen(const qgl__key *k)
{
    for (int u = 0; u < k->nunits; u++)
        for (int c = 0; c < 4; c++)
            if (k->unit[u].gen[c] >= QGL__G_SPHERE)
                return 1;
    return 0;
}

/* Lighting or a normal-based texgen reads the normal; only then do its scalings matter. */
static int reads_normal(const qgl__key *k)
{
    return (k->flags & QGL__KF_LIGHTING) || normal_texgen(k);
}

/* Per-vertex results not affine in the captured attributes. */
static int nonaffine(const qgl__state *st)
{
    const qgl__key *k = &st->ffp;
    return ((k->flags & QGL__KF_LIGHTING) && st->shade_model != GL_FLAT) || normal_texgen(k);
}

/* The per-vertex work reads the captured attributes and constants only, never the position:
 * no positional light, an infinite viewer, no texgen from the eye position (sphere map,
 * reflection map); linear texgen is affine in the position, which a planar quad is. */
static int lit_by_inputs(const qgl__state *st)
{
    const qgl__key *k = &st->ffp;
    if (k->light_pos || (k->flags & QGL__KF_LOCAL_VIEWER))
        return 0;
    for (int u = 0; u < k->nunits; u++)
        for (int c = 0; c < 4; c++)
            if (k->unit[u].gen[c] == QGL__G_SPHERE || k->unit[u].gen[c] == QGL__G_REFLECT)
                return 0;
    return 1;
}

/* Issue 4's subset (what the GLSL 1.20 path implements). */
static int simple(const qgl__key *k)
{
    if (k->flags || k->fog || k->clip || k->nunits > 1)
        return 0;
    const qgl__unit_key *u = &k->unit[0];
    return !u->target || (u->target == QGL__T_2D && (u->env == QGL__E_MODULATE || u->env == QGL__E_REPLACE) &&
                          u->format != QGL__F_ALPHA && !u->gen[0] && !u->gen[1] && !u->gen[2] && !u->gen[3]);
}

/* Fixed-function features and the key; returns 0 when the programs cannot reproduce them. */
static int query_ffp(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    qgl__key *k = &st->ffp;
    int ok = query_textures(ctx, st, k);
    if (gl->IsEnabled(GL_LIGHTING))
        query_lighting(ctx, k);
    else if (ctx->version >= 14 && gl->IsEnabled(GL_COLOR_SUM))
        k->flags |= QGL__KF_COLOR_SUM;
    if (reads_normal(k)) {
        if (gl->IsEnabled(GL_NORMALIZE))
            k->flags |= QGL__KF_NORMALIZE;
        else if (ctx->version >= 12 && gl->IsEnabled(GL_RESCALE_NORMAL))
            k->flags |= QGL__KF_RESCALE;
    }
    if (gl->IsEnabled(GL_FOG)) {
        query_fog(ctx, k);
        if (!(k->flags & QGL__KF_FOG_DEPTH))
            st->fog_slope = fog_slope(ctx, k);
    }
    for (GLint i = 0; i < ctx->max_clip_planes; i++)
        if (gl->IsEnabled(GL_CLIP_PLANE0 + (GLenum)i)) {
            if (i >= 8)
                ok = 0;
            else
                k->clip |= (uint8_t)(1u << i);
        }
    st->arb_program = (ctx->has_arb_vp && gl->IsEnabled(GL_VERTEX_PROGRAM_ARB)) ||
                      (ctx->has_arb_fp && gl->IsEnabled(GL_FRAGMENT_PROGRAM_ARB)) ||
                      (ctx->has_ati_fs && gl->IsEnabled(GL_FRAGMENT_SHADER_ATI));
    if (st->arb_program)
        ok = 0;
    /* the worst case of this state's programs (smooth, non-planar) must fit the varyings */
    qgl__key worst = *k;
    worst.flags |= QGL__KF_DEPTH | QGL__KF_PLANE;
    if (qgl__key_slots(&worst) > 30)
        ok = 0;
    return ok;
}

/* ---- the groups, read when the owner says they changed ---------------------------------------- */

static void query_raster(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    gl->GetIntegerv(GL_RENDER_MODE, &st->render_mode);
    gl->GetIntegerv(GL_POLYGON_MODE, st->polygon_mode);
    st->program = st->pipeline = 0;
    if (ctx->version >= 20)
        gl->GetIntegerv(GL_CURRENT_PROGRAM, &st->program);
    if (ctx->has_pipelines && !st->program) /* a bound program wins over the pipeline */
        gl->GetIntegerv(GL_PROGRAM_PIPELINE_BINDING, &st->pipeline);
    gl->GetIntegerv(GL_SHADE_MODEL, &st->shade_model);
    gl->GetIntegerv(GL_ACTIVE_TEXTURE, &st->active_texture);
    st->polygon_offset = gl->IsEnabled(GL_POLYGON_OFFSET_FILL);
    GLboolean clamp = GL_TRUE;
    if (ctx->shader_level && ctx->version >= 30) /* GL 3.0 state; GL 2.x always clamps */
        gl->GetBooleanv(GL_CLAMP_VERTEX_COLOR, &clamp);
    st->clamp = clamp;
    GLint pv = GL_LAST_VERTEX_CONVENTION;
    if (ctx->quads_follow_pv)
        gl->GetIntegerv(GL_PROVOKING_VERTEX, &pv);
    st->first_vertex_pv = pv == GL_FIRST_VERTEX_CONVENTION;
}

static void query_order(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    GLboolean mask = GL_FALSE;
    GLint func = GL_ALWAYS, bits = 0;
    gl->GetBooleanv(GL_DEPTH_WRITEMASK, &mask);
    gl->GetIntegerv(GL_DEPTH_FUNC, &func);
    gl->GetIntegerv(GL_DEPTH_BITS, &bits);
    st->blend_free = !gl->IsEnabled(GL_BLEND) && !gl->IsEnabled(GL_STENCIL_TEST) && !gl->IsEnabled(GL_COLOR_LOGIC_OP);
    st->order_free = gl->IsEnabled(GL_DEPTH_TEST) && mask && bits > 0 &&
                     (func == GL_LESS || func == GL_LEQUAL || func == GL_GREATER || func == GL_GEQUAL) &&
                     st->blend_free;
}

static void query_ffp_group(qgl_context *ctx, qgl__state *st)
{
    memset(&st->ffp, 0, sizeof st->ffp);
    memset(st->texsize, 0, sizeof st->texsize);
    st->fog_slope = 0;
    st->ffp_ok = query_ffp(ctx, st);
}

/* Only the bindings (or images) changed: the enabled units' textures' facts into the key
 * kept from the last full query; 0 when that must run (it failed, or a depth texture is
 * bound now). */
static int query_bound(qgl_context *ctx, qgl__state *st)
{
    qgl__key *k = &st->ffp;
    int ok = st->ffp_ok, switched = 0;
    for (int u = 0; u < k->nunits && ok; u++) {
        int t = k->unit[u].target ? target_index(k->unit[u].target) : -1;
        if (t < 0)
            continue;
        if (GL_TEXTURE0 + (GLint)u != st->active_texture)
            ctx->gl.ActiveTexture(GL_TEXTURE0 + (GLenum)u), switched = 1;
        const qgl__texfacts *f = texture_facts(ctx, t);
        ok = f->ok;
        if (k->unit[u].env != QGL__E_COMBINE)
            k->unit[u].format = f->format;
        memcpy(st->texsize[u], f->size, sizeof f->size);
    }
    if (switched)
        ctx->gl.ActiveTexture((GLenum)st->active_texture);
    return ok;
}

const double qgl__identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* Matrices (texture matrices of the units the key enables) and the viewport. */
static void query_xform(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    double pr[16];
    gl->GetIntegerv(GL_VIEWPORT, st->xf.viewport);
    gl->GetDoublev(GL_MODELVIEW_MATRIX, st->xf.modelview);
    gl->GetDoublev(GL_PROJECTION_MATRIX, pr);
    mat_mul(pr, st->xf.modelview, st->xf.mvp);
    int switched = 0;
    st->xf.texmat_identity = 0;
    for (int u = 0; u < st->ffp.nunits; u++) {
        if (!st->ffp.unit[u].target)
            continue;
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        gl->GetDoublev(GL_TEXTURE_MATRIX, st->xf.texmat[u]);
        st->xf.texmat_identity |= memcmp(st->xf.texmat[u], qgl__identity, sizeof qgl__identity) == 0 ? 1u << u : 0;
        switched = 1;
    }
    if (switched)
        gl->ActiveTexture((GLenum)st->active_texture);
}

static void query_bind(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    st->vao = st->array_buffer = 0;
    st->client_texture = GL_TEXTURE0;
    if (!ctx->has_vao)
        return;
    gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &st->vao);
    gl->GetIntegerv(GL_ARRAY_BUFFER_BINDING, &st->array_buffer);
    gl->GetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &st->client_texture);
}

/* What the planner concludes from the groups. */
static void derive(qgl_context *ctx, qgl__state *st)
{
    const qgl__unit_key *u0 = &st->ffp.unit[0];
    st->texture2d = u0->target == QGL__T_2D;
    st->tex_replace = u0->env == QGL__E_REPLACE;
    st->tex_no_alpha = u0->format == QGL__F_RGB;
    st->simple = simple(&st->ffp);
    st->own_pipeline = st->program != 0 || st->pipeline != 0 || st->arb_program;
    st->modelled = ctx->shader_level && st->ffp_ok && !st->own_pipeline && st->clamp &&
                   (ctx->shader_level == 150 || st->simple);
    st->nonaffine = st->own_pipeline || !st->ffp_ok || nonaffine(st); /* unknown work: assume the worst */
    st->lit_by_inputs = !st->own_pipeline && st->ffp_ok && lit_by_inputs(st);
    st->lit_cpu = !st->own_pipeline && st->ffp_ok && (st->ffp.flags & QGL__KF_LIGHTING) && st->shade_model != GL_FLAT &&
                  !normal_texgen(&st->ffp);
    st->pv_material = 0;
    st->quad_materials = 0;
}

void qgl__state_track(qgl_context *ctx)
{
    ctx->state_tracked = 1;
    ctx->state_valid = 0;
}

void qgl__state_dirty(qgl_context *ctx, unsigned groups)
{
    ctx->state_valid &= ~groups;
}

/* The state now, in ctx->state: read in full, or (an owner that marks changes) only the
 * groups changed since the last read; the rest is the copy kept from then. The preload
 * library asks for it at every primitive, so an unchanged state costs one test. */
const qgl__state *qgl__state_now(qgl_context *ctx)
{
    qgl__state *c = &ctx->state;
    unsigned need = ctx->state_tracked ? ~ctx->state_valid & QGL__D_ALL : QGL__D_ALL;
    if (!need)
        return c;
    if (need & QGL__D_FFP) {
        ctx->lightvals.lights_valid = 0;
        need |= QGL__D_LIGHT | QGL__D_XFORM; /* materials too; texture matrices of newly enabled units */
    }
    if (need & QGL__D_LIGHT)
        ctx->lightvals.materials_valid = 0;
    if (need & QGL__D_XFORM) {
        ctx->lightvals.normal_valid = 0;
        ctx->xform_stale = 1; /* read when a draw plans (qgl__state_xform): most split draws never do */
    }
    if (need & QGL__D_RASTER)
        query_raster(ctx, c);
    if (need & QGL__D_TEXIMAGE)
        memset(ctx->tex_facts, 0, sizeof ctx->tex_facts);
    if ((need & QGL__D_FFP) || ((need & (QGL__D_TEX | QGL__D_TEXIMAGE)) && !query_bound(ctx, c)))
        query_ffp_group(ctx, c);
    if (need & QGL__D_BIND)
        query_bind(ctx, c);
    if (need & QGL__D_ORDER)
        query_order(ctx, c);
    derive(ctx, c);
    ctx->state_valid = QGL__D_ALL;
    return c;
}

void qgl__state_xform(qgl_context *ctx, qgl__state *st)
{
    qgl__state *c = &ctx->state;
    if (ctx->xform_stale) {
        query_xform(ctx, c);
        ctx->xform_stale = 0;
    }
    if (st != c)
        st->xf = c->xf;
}

/* The state of this draw, into a copy the draw may adjust. */
void qgl__query_state(qgl_context *ctx, qgl__state *st)
{
    *st = *qgl__state_now(ctx);
}
