/* glsl120.c: the shader path for GL 2.x contexts without geometry shaders (GLSL 1.20).
 *
 * What the geometry shader does on GL 3.2 happens here on the CPU: each quad is classified
 * by the core (qgl_classify_clip) and its exact cover is emitted as plain triangles (convex:
 * two; concave: split through the reflex corner; bow-tie: the two lobes meeting at the
 * crossing point, whose object position is the perspective-correct point of the crossing
 * edge; a corner behind the eye: the clipped split, with the fragment shader killing what
 * lies outside the quad). Every emitted vertex carries, besides its own object position
 * (gl_Vertex, so ftransform gives the driver's own edges), the four corners' object
 * positions, colours and texture coordinates as generic attributes. The vertex shader turns
 * the corners into clip space and writes g_i = x_i W - X w_i, linear in clip space, so the
 * rasterizer's perspective interpolation hands the fragment shader W_f * s~_i(p), the same
 * positive multiple of the core's homogeneous s~_i the geometry shader path uses (x and y in
 * pixel units, scaled by the viewport's half size); the
 * corner values are constant over each triangle and reach the fragment shader unchanged.
 * The fragment shader is the core's robust formula in float. With the view-invariant weights
 * (QGL__K_PLANE) a planar quad's cover is computed in its own plane (qgl_plane_cover) and sent
 * in object space, each vertex with its s_i = q_i - q_v (in-plane corners less its own
 * in-plane position, affine on the surface) instead of the corner positions; a non-planar quad keeps the screen cover and g,
 * adds the corners' in-plane coordinates, and the fragment shader weighs its ray's hit on the
 * bilinear patch (as the geometry shader path does). Programs are generated from
 * draw.c's state key (only the features this file knows: colour, flat, one 2D texture
 * unit with MODULATE / REPLACE, eq. 4 depth, discard) and cached; a key with other bits, or
 * a program the driver refuses (GL 2.0 guarantees only 32 varying floats; colour plus
 * texture needs 44), makes the caller use the CPU fallback. With vertex array objects the
 * triangles are streamed from our own buffer behind our own object; without them (a real
 * GL 2.x context) they go as immediate-mode calls, and the current values of the generic
 * attributes we used are put back afterwards. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

/* Key bits this file implements; any other bit (a later feature) is declined. */
#define KNOWN_KEY (QGL__K_COLOR | QGL__K_FLAT | QGL__K_TEX | QGL__K_REPLACE | QGL__K_NOALPHA | QGL__K_DEPTH | \
                   QGL__K_DISCARD | QGL__K_PLANE | (3u << QGL__K_CORNER_SHIFT))

/* Generic attribute locations: corner positions (with the in-plane cover, the vertex's s_i in
 * the first two), corner colours, corner texture coordinates, and for the patch form the
 * corners' in-plane x and y. */
enum { LOC_POS = 1, LOC_COL = 5, LOC_TEX = 9, LOC_PLANE = 13, NLOC = 15 };

#define MAX_PROGRAMS 32

struct qgl__glsl120 {
    struct { unsigned key; GLuint prog; GLint px_loc; } programs[MAX_PROGRAMS];
    int nprograms;
    GLuint vao;
    float *buf;       /* interleaved emitted vertices */
    size_t buf_cap;   /* floats */
};

static const char vs_src[] =
    "varying vec4 v_g01, v_g23;\n"
    "#if PLANE_COVER\n"
    "attribute vec4 a_s01, a_s23;\n"
    "#else\n"
    "attribute vec4 a_p0, a_p1, a_p2, a_p3;\n"
    "#endif\n"
    "#if PLANE && !PLANE_COVER\n"
    "attribute vec4 a_qx, a_qy;\n"
    "varying vec4 v_qx, v_qy;\n"
    "#endif\n"
    "#if COLOR && FLAT\n"
    "attribute vec4 a_c0;\n"
    "varying vec4 v_flat;\n"
    "#elif COLOR\n"
    "attribute vec4 a_c0, a_c1, a_c2, a_c3;\n"
    "varying vec4 v_c0, v_c1, v_c2, v_c3;\n"
    "#endif\n"
    "#if TEX\n"
    "attribute vec4 a_t0, a_t1, a_t2, a_t3;\n"
    "varying vec3 v_t0, v_t1, v_t2, v_t3;\n"
    "#endif\n"
    "#if DEPTH\n"
    "varying vec4 v_w, v_z;\n"
    "#endif\n"
    "uniform vec2 u_px;\n"
    "vec2 g(vec4 C, vec4 X) { return (C.xy * X.w - X.xy * C.w) * u_px; }\n"
    "vec3 tex(vec4 t) { return (gl_TextureMatrix[0] * t).xyw; }\n"
    "void main() {\n"
    "    vec4 X = ftransform();\n"
    "    gl_Position = X;\n"
    "#if PLANE && !PLANE_COVER\n"
    "    v_qx = a_qx;\n"
    "    v_qy = a_qy;\n"
    "#endif\n"
    "#if PLANE_COVER\n"
    "    v_g01 = a_s01;\n"
    "    v_g23 = a_s23;\n"
    "#else\n"
    "    vec4 C0 = gl_ModelViewProjectionMatrix * a_p0, C1 = gl_ModelViewProjectionMatrix * a_p1;\n"
    "    vec4 C2 = gl_ModelViewProjectionMatrix * a_p2, C3 = gl_ModelViewProjectionMatrix * a_p3;\n"
    "    v_g01 = vec4(g(C0, X), g(C1, X));\n"
    "    v_g23 = vec4(g(C2, X), g(C3, X));\n"
    "#endif\n"
    "#if COLOR && FLAT\n"
    "    v_flat = clamp(a_c0, 0.0, 1.0);\n"
    "#elif COLOR\n"
    "    v_c0 = clamp(a_c0, 0.0, 1.0); v_c1 = clamp(a_c1, 0.0, 1.0);\n"
    "    v_c2 = clamp(a_c2, 0.0, 1.0); v_c3 = clamp(a_c3, 0.0, 1.0);\n"
    "#else\n"
    "    gl_FrontColor = clamp(gl_Color, 0.0, 1.0);\n"
    "#endif\n"
    "#if TEX\n"
    "    v_t0 = tex(a_t0); v_t1 = tex(a_t1); v_t2 = tex(a_t2); v_t3 = tex(a_t3);\n"
    "#endif\n"
    "#if DEPTH\n"
    "    v_w = vec4(C0.w, C1.w, C2.w, C3.w);\n"
    "    v_z = (vec4(C0.z / C0.w, C1.z / C1.w, C2.z / C2.w, C3.z / C3.w) * gl_DepthRange.diff\n"
    "           + (gl_DepthRange.near + gl_DepthRange.far)) * 0.5;\n"
    "#endif\n"
    "}\n";

/* The fragment shader; quad_weights() (shader.c's qgl__glsl_weights, the core's weights in
 * GLSL) and patch_hit() (qgl__glsl_patch) are put in front of it by compile(). */
static const char fs_src[] =
    "varying vec4 v_g01, v_g23;\n"
    "#if PLANE && !PLANE_COVER\n"
    "varying vec4 v_qx, v_qy;\n"
    "#endif\n"
    "#if COLOR && FLAT\n"
    "varying vec4 v_flat;\n"
    "#elif COLOR\n"
    "varying vec4 v_c0, v_c1, v_c2, v_c3;\n"
    "#endif\n"
    "#if TEX\n"
    "uniform sampler2D u_tex;\n"
    "varying vec3 v_t0, v_t1, v_t2, v_t3;\n"
    "#endif\n"
    "#if DEPTH\n"
    "varying vec4 v_w, v_z;\n"
    "#endif\n"
    "#if PLANE_COVER\n"
    "vec4 weights() {\n"
    "    return quad_weights(vec4(v_g01.x, v_g01.z, v_g23.x, v_g23.z), vec4(v_g01.y, v_g01.w, v_g23.y, v_g23.w));\n"
    "}\n"
    "#elif PLANE\n"
    "float patch_depth;\n"
    "vec4 weights() {\n"
    "    vec4 sx = vec4(v_g01.x, v_g01.z, v_g23.x, v_g23.z), sy = vec4(v_g01.y, v_g01.w, v_g23.y, v_g23.w);\n"
    "    float k = 1.0 / dot(abs(sx) + abs(sy), vec4(1.0));\n"
    "    vec4 b = patch_hit(sx * k, sy * k, v_w, v_z, patch_depth);\n"
    "    return quad_weights(v_qx - dot(b, v_qx), v_qy - dot(b, v_qy));\n"
    "}\n"
    "#else\n"
    "vec4 weights() {\n"
    "    return quad_weights_any(vec4(v_g01.x, v_g01.z, v_g23.x, v_g23.z), vec4(v_g01.y, v_g01.w, v_g23.y, v_g23.w));\n"
    "}\n"
    "#endif\n"
    "void main() {\n"
    "    vec4 lam = weights();\n"
    "#if DISCARD && !PLANE_COVER\n"
    "    if (any(lessThan(lam, vec4(-1e-5)))) discard;\n"
    "#endif\n"
    "#if COLOR && FLAT\n"
    "    vec4 col = v_flat;\n"
    "#elif COLOR\n"
    "    vec4 col = lam.x * v_c0 + lam.y * v_c1 + lam.z * v_c2 + lam.w * v_c3;\n"
    "#else\n"
    "    vec4 col = gl_Color;\n"
    "#endif\n"
    "#if TEX\n"
    "    vec3 tc = lam.x * v_t0 + lam.y * v_t1 + lam.z * v_t2 + lam.w * v_t3;\n"
    "    vec4 texel = texture2DProj(u_tex, tc);\n"
    "#if REPLACE && NOALPHA\n"
    "    col = vec4(texel.rgb, col.a);\n"
    "#elif REPLACE\n"
    "    col = texel;\n"
    "#else\n"
    "    col *= texel;\n"
    "#endif\n"
    "#endif\n"
    "    gl_FragColor = col;\n"
    "#if DEPTH && PLANE\n"
    "    gl_FragDepth = patch_depth;\n"
    "#elif DEPTH\n"
    "    vec4 scr = v_w * lam;\n"
    "    gl_FragDepth = dot(scr, v_z) / dot(scr, vec4(1.0));\n"
    "#endif\n"
    "}\n";

/* ---- programs ------------------------------------------------------------------------------ */

static GLuint compile(qgl_context *ctx, GLenum type, unsigned key, const char *body)
{
    struct qgl__gl *gl = &ctx->gl;
    char head[320];
    int plane = !!(key & QGL__K_PLANE), depth = !!(key & QGL__K_DEPTH);
    snprintf(head, sizeof head,
             "#version 120\n#define COLOR %d\n#define FLAT %d\n#define TEX %d\n#define REPLACE %d\n"
             "#define NOALPHA %d\n#define DEPTH %d\n#define DISCARD %d\n#define PLANE %d\n#define PLANE_COVER %d\n",
             !!(key & QGL__K_COLOR), !!(key & QGL__K_FLAT), !!(key & QGL__K_TEX), !!(key & QGL__K_REPLACE),
             !!(key & QGL__K_NOALPHA), depth, !!(key & QGL__K_DISCARD), plane, plane && !depth);
    int fs = type == GL_FRAGMENT_SHADER;
    const char *src[4] = {head, fs ? qgl__glsl_weights : "", fs && plane && depth ? qgl__glsl_patch : "", body};
    char log[2048];
    GLuint sh = qgl__shader_compile(gl, type, 4, src, log, sizeof log);
    if (!sh && getenv("QUADGL_DEBUG"))
        fprintf(stderr, "quadgl: GLSL 1.20 shader (key %#x) failed:\n%s\n", key, log);
    return sh;
}

static void bind_locations(struct qgl__gl *gl, GLuint prog)
{
    static const struct {
        const char *name;
        GLuint loc;
    } names[] = {{"a_p0", LOC_POS},     {"a_p1", LOC_POS + 1}, {"a_p2", LOC_POS + 2},   {"a_p3", LOC_POS + 3},
                 {"a_s01", LOC_POS},    {"a_s23", LOC_POS + 1}, {"a_c0", LOC_COL},      {"a_c1", LOC_COL + 1},
                 {"a_c2", LOC_COL + 2}, {"a_c3", LOC_COL + 3}, {"a_t0", LOC_TEX},      {"a_t1", LOC_TEX + 1},
                 {"a_t2", LOC_TEX + 2}, {"a_t3", LOC_TEX + 3}, {"a_qx", LOC_PLANE},    {"a_qy", LOC_PLANE + 1}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        gl->BindAttribLocation(prog, names[i].loc, names[i].name);
}

static GLuint link(qgl_context *ctx, unsigned key, GLuint vs, GLuint fs)
{
    struct qgl__gl *gl = &ctx->gl;
    GLuint prog = gl->CreateProgram();
    gl->AttachShader(prog, vs);
    gl->AttachShader(prog, fs);
    bind_locations(gl, prog);
    char log[2048];
    if (!qgl__program_link(gl, prog, log, sizeof log)) {
        if (getenv("QUADGL_DEBUG"))
            fprintf(stderr, "quadgl: GLSL 1.20 link (key %#x) failed:\n%s\n", key, log);
        gl->DeleteProgram(prog);
        return 0;
    }
    if (key & QGL__K_TEX) { /* the sampler reads unit 0 */
        GLint cur = 0;
        gl->GetIntegerv(GL_CURRENT_PROGRAM, &cur);
        gl->UseProgram(prog);
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_tex"), 0);
        gl->UseProgram((GLuint)cur);
    }
    return prog;
}

static GLuint build(qgl_context *ctx, unsigned key)
{
    GLuint vs = compile(ctx, GL_VERTEX_SHADER, key, vs_src);
    GLuint fs = vs ? compile(ctx, GL_FRAGMENT_SHADER, key, fs_src) : 0;
    GLuint prog = vs && fs ? link(ctx, key, vs, fs) : 0;
    if (vs)
        ctx->gl.DeleteShader(vs);
    if (fs)
        ctx->gl.DeleteShader(fs);
    return prog;
}

/* The corner index is not part of the program (the CPU picks the flat colour). */
static unsigned program_bits(unsigned key)
{
    return key & ~(3u << QGL__K_CORNER_SHIFT);
}

/* The program of key, and its u_px location in *px_loc. */
static GLuint program(qgl_context *ctx, unsigned key, GLint *px_loc)
{
    struct qgl__glsl120 *g = ctx->glsl120;
    unsigned bits = program_bits(key);
    for (int i = 0; i < g->nprograms; i++)
        if (g->programs[i].key == bits) {
            *px_loc = g->programs[i].px_loc;
            return g->programs[i].prog;
        }
    GLuint prog = build(ctx, bits);
    if (!prog)
        return 0;
    int slot = g->nprograms < MAX_PROGRAMS ? g->nprograms++ : (int)(bits % MAX_PROGRAMS);
    if (g->programs[slot].prog)
        ctx->gl.DeleteProgram(g->programs[slot].prog);
    g->programs[slot].key = bits;
    g->programs[slot].prog = prog;
    g->programs[slot].px_loc = *px_loc = ctx->gl.GetUniformLocation(prog, "u_px");
    return prog;
}

/* ---- life cycle ---------------------------------------------------------------------------- */

int qgl__glsl120_supported(qgl_context *ctx)
{
    struct qgl__gl *gl = &ctx->gl;
    if (ctx->version < 20 || !gl->CreateShader || !gl->BindAttribLocation || !gl->VertexAttrib4fv ||
        !gl->GetVertexAttribfv)
        return 0;
    const char *s = (const char *)gl->GetString(GL_SHADING_LANGUAGE_VERSION);
    int major = 0, minor = 0;
    if (!s || sscanf(s, "%d.%d", &major, &minor) != 2)
        return 0;
    return major * 100 + minor >= 120;
}

int qgl__glsl120_init(qgl_context *ctx)
{
    ctx->glsl120 = calloc(1, sizeof *ctx->glsl120);
    if (!ctx->glsl120)
        return 0;
    if (ctx->has_vao && ctx->gl.VertexAttribPointer && ctx->gl.EnableVertexAttribArray) {
        GLint vao = 0;
        ctx->gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
        ctx->gl.GenVertexArrays(1, &ctx->glsl120->vao);
        ctx->gl.BindVertexArray((GLuint)vao);
    }
    GLint px_loc;
    if (program(ctx, QGL__K_COLOR, &px_loc)) /* proves the path works on this driver */
        return 1;
    qgl__glsl120_free(ctx);
    return 0;
}

void qgl__glsl120_free(qgl_context *ctx)
{
    struct qgl__glsl120 *g = ctx->glsl120;
    if (!g)
        return;
    for (int i = 0; i < g->nprograms && !ctx->gl_gone; i++)
        ctx->gl.DeleteProgram(g->programs[i].prog);
    if (g->vao && !ctx->gl_gone) {
        ctx->gl.DeleteVertexArrays(1, &g->vao);
    }
    free(g->buf);
    free(g);
    ctx->glsl120 = NULL;
}

/* ---- the cover, emitted vertex by vertex ------------------------------------------------------ */

typedef struct layout {
    int cover;      /* the in-plane cover: each vertex carries its own s_i (2 vec4s) */
    int npos;       /* corner positions (4, for g; 0 with the in-plane cover) */
    int nplane;     /* the corners' in-plane x and y (2, the patch form), or none */
    int ncol, ntex; /* corner colours (0, 1 flat or 4) and texture coordinates (0 or 4) */
    int stride;     /* floats per emitted vertex */
} layout;

static layout layout_of(unsigned key)
{
    layout l;
    int plane = (key & QGL__K_PLANE) != 0;
    l.cover = plane && !(key & QGL__K_DEPTH);
    l.npos = l.cover ? 0 : 4;
    l.nplane = plane && !l.cover ? 2 : 0;
    l.ncol = !(key & QGL__K_COLOR) ? 0 : (key & QGL__K_FLAT) ? 1 : 4;
    l.ntex = key & QGL__K_TEX ? 4 : 0;
    l.stride = 4 * (1 + 2 * l.cover + l.npos + l.nplane + l.ncol + l.ntex);
    return l;
}

static void copy4(float *d, const float *s)
{
    d[0] = s[0], d[1] = s[1], d[2] = s[2], d[3] = s[3];
}

/* A quad's in-plane corners (scaled to at most 1, as the geometry shader does) as the two
 * vec4s qx, qy, and its plane; 0 when the corners span no plane. A corner at infinity in
 * object space makes NDC stand in, as in the geometry shader. */
typedef struct plane_quad {
    qgl_plane pl;
    double scale;
    float q[2][4];
} plane_quad;

static int plane_of(const qgl_context *ctx, const qgl__verts *v, const size_t idx[4], plane_quad *pq)
{
    double pos[4][3], m = 0;
    int finite = 1;
    for (int c = 0; c < 4; c++)
        finite &= v->pos[4 * idx[c] + 3] > 0;
    for (int c = 0; c < 4; c++) {
        const float *p = v->pos + 4 * idx[c];
        const double *h = ctx->clip + 4 * idx[c];
        double w = finite ? p[3] : h[3];
        if (!(w > 0))
            return 0;
        for (int k = 0; k < 3; k++)
            pos[c][k] = (finite ? p[k] : h[k]) / w;
    }
    if (qgl_plane_frame(pos, &pq->pl) != 0)
        return 0;
    for (int c = 0; c < 4; c++)
        m = fmax(m, fmax(fabs(pq->pl.corner[c][0]), fabs(pq->pl.corner[c][1])));
    pq->scale = 1 / m;
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 2; k++)
            pq->q[k][c] = (float)(pq->pl.corner[c][k] * pq->scale);
    return 1;
}

/* What every vertex of quad q carries after its own position (and in-plane position): corner
 * positions, in-plane corners, colours, texture coordinates (the current colour when the
 * quads have none). */
static void corner_block(const qgl__verts *v, const size_t idx[4], const layout *l, const plane_quad *pq, int flat,
                         const float cur[4], float *out)
{
    for (int c = 0; c < l->npos; c++)
        copy4(out + 4 * c, v->pos + 4 * idx[c]);
    out += 4 * l->npos;
    for (int k = 0; k < l->nplane; k++)
        copy4(out + 4 * k, pq->q[k]);
    out += 4 * l->nplane;
    for (int c = 0; c < l->ncol; c++) {
        size_t i = idx[l->ncol == 1 ? flat : c];
        copy4(out + 4 * c, v->mask & QGL__A_COLOR ? v->col + 4 * i : cur);
    }
    out += 4 * l->ncol;
    static const float tex_default[4] = {0, 0, 0, 1};
    for (int c = 0; c < l->ntex; c++)
        copy4(out + 4 * c, v->mask & QGL__A_TEX0 ? v->tex[0] + 4 * idx[c] : tex_default);
}

/* Object position of the bow-tie's crossing point: the point of edge (a, a+1) at parameter t
 * there, made homogeneous with w (the clip w for a screen parameter, the object w for an
 * in-plane one). */
static void crossing_point(const qgl__verts *v, const size_t idx[4], int a, double t, double wa, double wb,
                           float out[4])
{
    double s = t * wa / ((1 - t) * wb + t * wa);
    for (int k = 0; k < 4; k++)
        out[k] = (float)((1 - s) * v->pos[4 * idx[a] + k] + s * v->pos[4 * idx[a + 1] + k]);
}

static int reserve(struct qgl__glsl120 *g, size_t floats)
{
    if (floats <= g->buf_cap)
        return 1;
    size_t cap = floats > 2 * g->buf_cap ? floats : 2 * g->buf_cap;
    float *p = realloc(g->buf, cap * sizeof(float));
    if (!p)
        return 0;
    g->buf = p;
    g->buf_cap = cap;
    return 1;
}

/* The screen cover of quad q (corners behind the eye: the split, clipped by the driver, the
 * shader killing what lies outside) and the crossing point's object position; 0 when the
 * quad has no interior on screen. */
static int screen_cover(qgl_context *ctx, const qgl__verts *v, const size_t idx[4], qgl_cover *cov, float cross[4])
{
    double clip[4][4];
    for (int c = 0; c < 4; c++)
        memcpy(clip[c], ctx->clip + 4 * idx[c], sizeof clip[c]);
    int kind = qgl_classify_clip(clip, cov);
    if (kind == QGL_QUAD_EXTERNAL) {
        cov->ntri = 2;
        static const unsigned char split[2][3] = {{0, 1, 3}, {1, 2, 3}}; /* the driver's */
        memcpy(cov->tri, split, sizeof split);
    } else if (kind < 0 || kind == QGL_QUAD_DEGENERATE) {
        return 0;
    } else if (kind == QGL_QUAD_BOWTIE) {
        int a = cov->cross_edge;
        crossing_point(v, idx, a, cov->cross_t, clip[a][3], clip[a + 1][3], cross);
    }
    return 1;
}

/* Append the cover of quad q; returns the number of vertices written, -1 without memory. The
 * in-plane cover is exact whatever the camera (the clipper cuts it where corners are behind
 * the eye); every vertex then carries its in-plane position too. */
static int emit_quad(qgl_context *ctx, const qgl__verts *v, qgl_topology topo, size_t q, const layout *l,
                     int flat, const float cur[4], size_t at)
{
    struct qgl__glsl120 *g = ctx->glsl120;
    size_t idx[4];
    for (int c = 0; c < 4; c++)
        idx[c] = qgl__corner(topo, q, c);
    qgl_cover cov;
    plane_quad pq;
    float cross[4] = {0, 0, 0, 1}, own[5][8];
    if ((l->nplane || l->cover) && !plane_of(ctx, v, idx, &pq))
        return 0;
    if (l->cover) {
        int kind = qgl_plane_cover(&pq.pl, &cov);
        if (kind < 0 || kind == QGL_QUAD_DEGENERATE)
            return 0;
        int a = cov.cross_edge;
        if (kind == QGL_QUAD_BOWTIE)
            crossing_point(v, idx, a, cov.cross_t, v->pos[4 * idx[a] + 3], v->pos[4 * idx[a + 1] + 3], cross);
        /* each cover vertex's s_i = q_i - q_v, scaled as the corners */
        for (int c = 0; c < 5; c++)
            for (int i = 0; i < 4; i++)
                for (int k = 0; k < 2; k++)
                    own[c][2 * i + k] = (float)((pq.pl.corner[i][k] - (c < 4 ? pq.pl.corner[c][k] : cov.cross[k])) *
                                                pq.scale);
    } else if (!screen_cover(ctx, v, idx, &cov, cross)) {
        return 0;
    }
    size_t stride = (size_t)l->stride, head = 4 * (size_t)(1 + 2 * l->cover);
    if (!reserve(g, (at + 3 * (size_t)cov.ntri) * stride))
        return -1;
    float block[96];
    corner_block(v, idx, l, &pq, flat, cur, block);
    float *out = g->buf + at * stride;
    for (int t = 0; t < cov.ntri; t++)
        for (int k = 0; k < 3; k++, out += stride) {
            int c = cov.tri[t][k];
            copy4(out, c == 4 ? cross : v->pos + 4 * idx[c]);
            if (l->cover)
                memcpy(out + 4, own[c], sizeof own[c]);
            memcpy(out + head, block, (stride - head) * sizeof(float));
        }
    return 3 * cov.ntri;
}

/* ---- submission -------------------------------------------------------------------------------- */

/* The generic locations of the nattr attributes of a layout after the position; attribute a
 * sits at float 4 (1 + a) of an emitted vertex. Returns nattr. */
static int locations(const layout *l, GLuint loc[NLOC - 1])
{
    int n = 0;
    for (int k = 0; k < 2 * l->cover; k++)
        loc[n++] = (GLuint)(LOC_POS + k);
    for (int c = 0; c < l->npos; c++)
        loc[n++] = (GLuint)(LOC_POS + c);
    for (int k = 0; k < l->nplane; k++)
        loc[n++] = (GLuint)(LOC_PLANE + k);
    for (int c = 0; c < l->ncol; c++)
        loc[n++] = (GLuint)(LOC_COL + c);
    for (int c = 0; c < l->ntex; c++)
        loc[n++] = (GLuint)(LOC_TEX + c);
    return n;
}

/* Stream through the stream buffer behind our vertex array object (the caller restores the
 * bindings); 0 when the driver refused the buffer. */
static int submit_arrays(qgl_context *ctx, const layout *l, size_t n)
{
    struct qgl__gl *gl = &ctx->gl;
    struct qgl__glsl120 *g = ctx->glsl120;
    size_t bytes = n * (size_t)l->stride * sizeof(float), off = 0;
    GLsizei stride = (GLsizei)(l->stride * sizeof(float));
    gl->BindVertexArray(g->vao);
    void *map = qgl__stream_begin(ctx, bytes, &off);
    if (!map)
        return 0;
    memcpy(map, g->buf, bytes);
    qgl__stream_end(ctx);
    gl->VertexPointer(4, GL_FLOAT, stride, (const void *)(uintptr_t)off);
    gl->EnableClientState(GL_VERTEX_ARRAY);
    for (int i = 0; i < NLOC - 1; i++) /* a previous key may have used more */
        gl->DisableVertexAttribArray((GLuint)(LOC_POS + i));
    GLuint loc[NLOC - 1];
    int nattr = locations(l, loc);
    for (int a = 0; a < nattr; a++) {
        gl->VertexAttribPointer(loc[a], 4, GL_FLOAT, GL_FALSE, stride, (const void *)(uintptr_t)(off + 16 * (1 + a)));
        gl->EnableVertexAttribArray(loc[a]);
    }
    gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)n);
    gl->BindVertexArray(ctx->vao); /* later runs of the batch draw from the batch's arrays */
    return 1;
}

/* Immediate mode, for contexts without vertex array objects: the application's arrays stay
 * untouched; the generic attributes' current values are saved and put back. */
static void submit_immediate(qgl_context *ctx, const layout *l, size_t n)
{
    struct qgl__gl *gl = &ctx->gl;
    GLuint loc[NLOC - 1];
    float saved[NLOC - 1][4];
    int nattr = locations(l, loc);
    for (int a = 0; a < nattr; a++)
        gl->GetVertexAttribfv(loc[a], GL_CURRENT_VERTEX_ATTRIB, saved[a]);
    const float *p = ctx->glsl120->buf;
    gl->Begin(GL_TRIANGLES);
    for (size_t i = 0; i < n; i++, p += l->stride) {
        for (int a = 0; a < nattr; a++)
            gl->VertexAttrib4fv(loc[a], p + 4 * (1 + a));
        gl->Vertex4fv(p);
    }
    gl->End();
    for (int a = 0; a < nattr; a++)
        gl->VertexAttrib4fv(loc[a], saved[a]);
}

int qgl__glsl120_draw(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q0,
                      size_t nq, unsigned key, GLint *bound)
{
    if (!ctx->glsl120 || (key & ~(unsigned)KNOWN_KEY))
        return 0;
    GLint px_loc = -1;
    GLuint prog = program(ctx, key, &px_loc);
    if (!prog)
        return 0;
    layout l = layout_of(key);
    int flat = (int)((key >> QGL__K_CORNER_SHIFT) & 3);
    float cur[4] = {1, 1, 1, 1};
    if (l.ncol && !(v->mask & QGL__A_COLOR))
        ctx->gl.GetFloatv(GL_CURRENT_COLOR, cur);
    size_t n = 0;
    for (size_t q = q0; q < q0 + nq; q++) {
        int k = emit_quad(ctx, v, topo, q, &l, flat, cur, n);
        if (k < 0)
            return 0;
        n += (size_t)k;
    }
    if (!n)
        return 1;
    ctx->stats.draws++;
    if (*bound != (GLint)prog)
        ctx->gl.UseProgram(prog), *bound = (GLint)prog;
    /* the weights in isotropic pixel units: x and y scaled by the viewport's half size */
    ctx->gl.Uniform2f(px_loc, 0.5f * (float)st->xf.viewport[2], 0.5f * (float)st->xf.viewport[3]);
    if (!ctx->glsl120->vao || !submit_arrays(ctx, &l, n))
        submit_immediate(ctx, &l, n);
    if (!ctx->has_vao) /* no restore() follows: give the application its program back now */
        ctx->gl.UseProgram((GLuint)(*bound = st->program));
    return 1;
}
