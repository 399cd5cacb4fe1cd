/* shader.c: GLSL programs of the shader path, generated from a small state key and cached.
 *
 * Vertex shader: the driver's own per-vertex work for the modelled state (ftransform, which
 * GLSL guarantees invariant with fixed function, so our edges meet the driver's exactly;
 * clamped colour; texture matrix of unit 0). Geometry shader (lines_adjacency: the four
 * corners of one quad): classifies the screen quad and emits its exact cover in clip space
 * (convex: two triangles; concave: split through the reflex corner; bow-tie: the two lobes
 * meeting at the crossing point, each keeping its own winding, so facing and culling are per
 * lobe; a corner at or behind the eye: the clipped split, with the fragment shader killing
 * what lies outside the quad). It passes the corners' attributes flat, and the vectors
 * g_i = x_i W - X w_i (clip corner i against the emitted vertex X), which are linear in clip
 * space: perspective interpolation makes them W_f * s~_i(p), a positive multiple of the
 * homogeneous s~_i of the core, which leaves the weights unchanged. Fragment shader: the
 * core's robust formula in float (tangent of half angles in the non-cancelling form, the
 * limits on corners and on edge segments), then colour, texture and, for non-planar quads
 * only, window depth from the screen weights. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

static const char vs_src[] =
    "void main() {\n"
    "    gl_Position = ftransform();\n"
    "#if COLOR\n"
    "    q_col = clamp(gl_Color, 0.0, 1.0);\n"
    "#endif\n"
    "#if TEX\n"
    "    q_tex = gl_TextureMatrix[0] * gl_MultiTexCoord0;\n"
    "#endif\n"
    "}\n";

static const char gs_src[] =
    "layout(lines_adjacency) in;\n"
    "layout(triangle_strip, max_vertices = 6) out;\n"
    "#if COLOR\n"
    "in vec4 q_col[];\n"
    "#endif\n"
    "#if TEX\n"
    "in vec4 q_tex[];\n"
    "#endif\n"
    "vec4 C[4];\n"
    "void emit(vec4 X) {\n"
    "    gl_Position = X;\n"
    "    g0 = C[0].xy * X.w - X.xy * C[0].w;\n"
    "    g1 = C[1].xy * X.w - X.xy * C[1].w;\n"
    "    g2 = C[2].xy * X.w - X.xy * C[2].w;\n"
    "    g3 = C[3].xy * X.w - X.xy * C[3].w;\n"
    "#if COLOR && FLAT\n"
    "    f_flat = q_col[CORNER];\n"
    "#elif COLOR\n"
    "    f_col = mat4(q_col[0], q_col[1], q_col[2], q_col[3]);\n"
    "#endif\n"
    "#if TEX\n"
    "    f_tex = mat4(q_tex[0], q_tex[1], q_tex[2], q_tex[3]);\n"
    "#endif\n"
    "#if DEPTH\n"
    "    f_w = vec4(C[0].w, C[1].w, C[2].w, C[3].w);\n"
    "    f_z = (vec4(C[0].z / C[0].w, C[1].z / C[1].w, C[2].z / C[2].w, C[3].z / C[3].w)\n"
    "           * gl_DepthRange.diff + (gl_DepthRange.near + gl_DepthRange.far)) * 0.5;\n"
    "#endif\n"
    "    EmitVertex();\n"
    "}\n"
    "void tri(vec4 a, vec4 b, vec4 c) { emit(a); emit(b); emit(c); EndPrimitive(); }\n"
    "float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }\n"
    /* the clip point on edge a->b whose projection is at screen parameter t */
    "vec4 on_edge(int a, int b, float t) {\n"
    "    float s = t * C[a].w / ((1.0 - t) * C[b].w + t * C[a].w);\n"
    "    return mix(C[a], C[b], s);\n"
    "}\n"
    /* screen parameters (t on a->b, u on c->d) of the crossing of two segments */
    "vec2 crossing(vec2 a, vec2 b, vec2 c, vec2 d) {\n"
    "    float den = cross2(b - a, d - c);\n"
    "    if (den == 0.0) return vec2(-1.0);\n"
    "    return vec2(cross2(c - a, d - c), cross2(c - a, b - a)) / den;\n"
    "}\n"
    "bool inside01(vec2 tu) { return all(greaterThanEqual(tu, vec2(0.0))) && all(lessThanEqual(tu, vec2(1.0))); }\n"
    "void main() {\n"
    "    for (int i = 0; i < 4; i++) C[i] = gl_in[i].gl_Position;\n"
    "    vec4 w = vec4(C[0].w, C[1].w, C[2].w, C[3].w);\n"
    "    if (any(lessThanEqual(w, vec4(0.0)))) {\n"
    "        if (all(lessThanEqual(w, vec4(0.0)))) return;\n"
    "        tri(C[0], C[1], C[2]); tri(C[0], C[2], C[3]);\n"
    "        return;\n"
    "    }\n"
    "    vec2 v[4];\n"
    "    for (int i = 0; i < 4; i++) v[i] = C[i].xy / C[i].w;\n"
    "    int npos = 0, nneg = 0, ipos = 0, ineg = 0;\n"
    "    for (int i = 0; i < 4; i++) {\n"
    "        float k = cross2(v[i] - v[(i + 3) & 3], v[(i + 1) & 3] - v[i]);\n"
    "        if (k > 0.0) { npos++; ipos = i; }\n"
    "        if (k < 0.0) { nneg++; ineg = i; }\n"
    "    }\n"
    "    if (npos + nneg == 0) return;\n"
    "    if (npos == 0 || nneg == 0) { tri(C[0], C[1], C[2]); tri(C[0], C[2], C[3]); return; }\n"
    "    if (npos != nneg) {\n"
    "        int r = npos < nneg ? ipos : ineg;\n"
    "        tri(C[r], C[(r + 1) & 3], C[(r + 2) & 3]); tri(C[r], C[(r + 2) & 3], C[(r + 3) & 3]);\n"
    "        return;\n"
    "    }\n"
    "    vec2 tu = crossing(v[0], v[1], v[2], v[3]);\n"
    "    if (inside01(tu)) {\n"
    "        vec4 X = on_edge(0, 1, tu.x);\n"
    "        tri(X, C[1], C[2]); tri(X, C[3], C[0]);\n"
    "        return;\n"
    "    }\n"
    "    tu = crossing(v[1], v[2], v[3], v[0]);\n"
    "    if (inside01(tu)) {\n"
    "        vec4 X = on_edge(1, 2, tu.x);\n"
    "        tri(X, C[2], C[3]); tri(X, C[0], C[1]);\n"
    "        return;\n"
    "    }\n"
    "    tri(C[0], C[1], C[2]); tri(C[0], C[2], C[3]);\n"
    "}\n";

static const char fs_src[] =
    "#if TEX\n"
    "uniform sampler2D u_tex;\n"
    "#endif\n"
    /* The core's weights (libquadgl/core/weights_impl.h) in float, four corners at once. */
    "vec4 weights() {\n"
    "    vec4 sx = vec4(g0.x, g1.x, g2.x, g3.x), sy = vec4(g0.y, g1.y, g2.y, g3.y);\n"
    "    vec4 sxn = sx.yzwx, syn = sy.yzwx;\n"
    "    vec4 rho = sqrt(sx * sx + sy * sy);\n"
    "    vec4 rhon = rho.yzwx;\n"
    "    vec4 A = sx * syn - sy * sxn;\n"
    "    vec4 D = sx * sxn + sy * syn;\n"
    "    vec4 P = rho * rhon;\n"
    "    bvec4 pd = greaterThan(D, vec4(0.0));\n"
    "    vec4 t = mix(P - D, A, pd) / mix(A, P + D, pd);\n"
    "    vec4 nu = (t.wxyz + t) / rho;\n"
    "    vec4 lam = nu / dot(nu, vec4(1.0));\n"
    "    float rsum = dot(rho, vec4(1.0));\n"
    "    vec4 onv = step(rho, vec4(1e-6 * rsum));\n"
    "    vec4 one = step(abs(A), 1e-6 * (P - D)) * step(D, vec4(0.0));\n"
    "    float nv = dot(onv, vec4(1.0)), ne = dot(one, vec4(1.0));\n"
    "    if (ne > 0.0) {\n"
    "        vec4 rs = rho + rhon;\n"
    "        lam = (one * rhon / rs + (one * rho / rs).wxyz) / ne;\n"
    "    }\n"
    "    if (nv > 0.0) lam = onv / nv;\n"
    "    return lam;\n"
    "}\n"
    "void main() {\n"
    "    vec4 lam = weights();\n"
    "#if DISCARD\n"
    "    if (any(lessThan(lam, vec4(0.0)))) discard;\n"
    "#endif\n"
    "#if COLOR && FLAT\n"
    "    vec4 col = f_flat;\n"
    "#elif COLOR\n"
    "    vec4 col = f_col * lam;\n"
    "#else\n"
    "    vec4 col = gl_Color;\n"
    "#endif\n"
    "#if TEX\n"
    "    vec4 tc = f_tex * lam;\n"
    "    vec4 texel = textureProj(u_tex, tc.xyw);\n"
    "#if REPLACE && NOALPHA\n"
    "    col = vec4(texel.rgb, col.a);\n"
    "#elif REPLACE\n"
    "    col = texel;\n"
    "#else\n"
    "    col *= texel;\n"
    "#endif\n"
    "#endif\n"
    "    gl_FragColor = col;\n"
    "#if DEPTH\n"
    "    vec4 scr = f_w * lam;\n"
    "    gl_FragDepth = dot(scr, f_z) / dot(scr, vec4(1.0));\n"
    "#endif\n"
    "}\n";

/* Interface blocks would tie stage names together; plain declarations per stage are simpler
 * and every stage sees only what its key enables. */
static void header(char *buf, size_t n, unsigned key, int stage)
{
    static const char *const io[3][2] = {{"", "out"}, {"in", "out"}, {"in", ""}};
    int len = snprintf(buf, n,
                       "#version 150 compatibility\n#define COLOR %d\n#define FLAT %d\n#define TEX %d\n"
                       "#define REPLACE %d\n#define NOALPHA %d\n#define DEPTH %d\n#define DISCARD %d\n"
                       "#define CORNER %u\n",
                       !!(key & QGL__K_COLOR), !!(key & QGL__K_FLAT), !!(key & QGL__K_TEX),
                       !!(key & QGL__K_REPLACE), !!(key & QGL__K_NOALPHA), !!(key & QGL__K_DEPTH),
                       !!(key & QGL__K_DISCARD), (key >> QGL__K_CORNER_SHIFT) & 3);
    const char *in = io[stage][0], *out = io[stage][1];
    if (stage == 0)
        len += snprintf(buf + len, n - len, "#if COLOR\nout vec4 q_col;\n#endif\n#if TEX\nout vec4 q_tex;\n#endif\n");
    if (stage >= 1) {
        const char *dir = stage == 1 ? out : in;
        len += snprintf(buf + len, n - len,
                        "%s vec2 g0, g1, g2, g3;\n"
                        "#if COLOR && FLAT\nflat %s vec4 f_flat;\n#elif COLOR\nflat %s mat4 f_col;\n#endif\n"
                        "#if TEX\nflat %s mat4 f_tex;\n#endif\n"
                        "#if DEPTH\nflat %s vec4 f_w, f_z;\n#endif\n",
                        dir, dir, dir, dir, dir);
    }
}

static GLuint compile(qgl_context *ctx, GLenum type, unsigned key, int stage, const char *body)
{
    struct qgl__gl *gl = &ctx->gl;
    char head[1024];
    header(head, sizeof head, key, stage);
    const char *src[2] = {head, body};
    GLuint sh = gl->CreateShader(type);
    gl->ShaderSource(sh, 2, src, NULL);
    gl->CompileShader(sh);
    GLint ok = 0;
    gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        gl->GetShaderInfoLog(sh, sizeof log, NULL, log);
        if (getenv("QUADGL_DEBUG"))
            fprintf(stderr, "quadgl: shader (key %#x, stage %d) failed:\n%s\n", key, stage, log);
        gl->DeleteShader(sh);
        return 0;
    }
    return sh;
}

static GLuint build(qgl_context *ctx, unsigned key)
{
    struct qgl__gl *gl = &ctx->gl;
    GLuint vs = compile(ctx, GL_VERTEX_SHADER, key, 0, vs_src);
    GLuint gs = compile(ctx, GL_GEOMETRY_SHADER, key, 1, gs_src);
    GLuint fs = compile(ctx, GL_FRAGMENT_SHADER, key, 2, fs_src);
    GLuint prog = 0;
    if (vs && gs && fs) {
        prog = gl->CreateProgram();
        gl->AttachShader(prog, vs);
        gl->AttachShader(prog, gs);
        gl->AttachShader(prog, fs);
        gl->LinkProgram(prog);
        GLint ok = 0;
        gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            char log[2048];
            gl->GetProgramInfoLog(prog, sizeof log, NULL, log);
            if (getenv("QUADGL_DEBUG"))
                fprintf(stderr, "quadgl: link (key %#x) failed:\n%s\n", key, log);
            gl->DeleteProgram(prog);
            prog = 0;
        }
    }
    if (vs)
        gl->DeleteShader(vs);
    if (gs)
        gl->DeleteShader(gs);
    if (fs)
        gl->DeleteShader(fs);
    if (prog && (key & QGL__K_TEX)) { /* the sampler reads unit 0 */
        GLint cur = 0;
        gl->GetIntegerv(GL_CURRENT_PROGRAM, &cur);
        gl->UseProgram(prog);
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_tex"), 0);
        gl->UseProgram((GLuint)cur);
    }
    return prog;
}

/* The program for key, built on first use; 0 when it cannot be built. */
GLuint qgl__program(qgl_context *ctx, unsigned key)
{
    for (int i = 0; i < ctx->nprograms; i++)
        if (ctx->programs[i].key == key)
            return ctx->programs[i].prog;
    GLuint prog = build(ctx, key);
    if (!prog)
        return 0;
    int slot = ctx->nprograms < QGL__MAX_PROGRAMS ? ctx->nprograms++ : (int)(key % QGL__MAX_PROGRAMS);
    if (slot < ctx->nprograms - 1 || ctx->programs[slot].prog) /* full: evict */
        ctx->gl.DeleteProgram(ctx->programs[slot].prog);
    ctx->programs[slot].key = key;
    ctx->programs[slot].prog = prog;
    return prog;
}

void qgl__programs_free(qgl_context *ctx)
{
    for (int i = 0; i < ctx->nprograms; i++)
        ctx->gl.DeleteProgram(ctx->programs[i].prog);
    ctx->nprograms = 0;
}
