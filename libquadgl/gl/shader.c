/* shader.c: GLSL programs of the shader path, generated from a fixed-function key and cached.
 *
 * Vertex shader: the driver's own per-vertex work, per corner, for exactly the features the
 * key enables: ftransform (which GLSL guarantees invariant with fixed function, so our edges
 * meet the driver's), lighting (each enabled light directional, positional or spot, with
 * attenuation, local viewer, two sides, colour material, per-vertex materials, separate
 * specular, NORMALIZE / RESCALE_NORMAL), clamped colours, secondary colour, texgen (object
 * and eye linear, sphere, reflection and normal map) and the texture matrix of every unit,
 * the fog coordinate (given, or the eye depth |z_e|) and the eye position for clip planes.
 * Parameters are the compatibility profile's built-in uniforms (gl_LightSource,
 * gl_FrontMaterial, gl_EyePlaneS, gl_Fog, gl_ClipPlane...), which the driver keeps current,
 * so a program depends on the key only and nothing is uploaded per draw.
 * Geometry shader (lines_adjacency: the four corners of one quad): classifies the screen quad
 * and emits its exact cover in clip space (convex: two triangles; concave: split through the
 * reflex corner; bow-tie: the two lobes meeting at the crossing point, each keeping its own
 * winding, so facing is per lobe; a corner at or behind the eye: the clipped split, with the
 * fragment shader killing what lies outside the quad). It passes the corners' per-vertex
 * results flat (one mat4 per vec4 result: column i is corner i; texture coordinates as one
 * vec4 of the four corners per component the target reads), and g_i = x_i - w_i X/W
 * (clip corner i against the emitted vertex X), affine in the window: interpolated without
 * perspective they are s~_i(p), the core's homogeneous s~_i, times one scale per quad that
 * keeps them near 1 and leaves the weights unchanged (no per-fragment normalisation). Where
 * the driver clips (a corner outside the view volume or behind the eye, clip planes) g_i =
 * x_i W - X w_i instead, linear in clip space, perspective-interpolated (W_f * s~_i) and
 * normalised per fragment.
 * x and y are scaled by the viewport's half size (u_px), so
 * the weights are those of the quad as it appears in pixels, whatever the viewport's aspect
 * (in NDC a wide window would squeeze the quad). Clip distances come from the corners' eye positions
 * (exact for planar quads, as the driver's own clipping); a non-planar quad is clipped per
 * fragment at its interpolated eye position instead.
 * View-invariant forms (QGL__KF_PLANE: AUTO, MVC_PLANE): screen-space weights change with the
 * camera, weights in the quad's own plane do not. The geometry shader builds the plane frame
 * of the corners' object positions (core plane.c in float) and, for a planar quad, emits the
 * quad's cover in that plane (exact whatever the camera: the clipper cuts it where corners are
 * behind the eye, so nothing outside the quad is drawn and no fragment is killed), each
 * vertex v carrying s_i = q_i - q_v, the in-plane corners less its own in-plane position, in
 * gA and gB: affine on the surface, perspective-interpolated they are each fragment's own
 * s_i exactly, so the fragment shader is the screen form's, and depth is the rasterizer's
 * own. Where the driver does not clip, s_i / w_v is sent instead, interpolated without
 * perspective: that is the fragment's s_i times 1 / w of the fragment, a positive factor the
 * weights do not see, so no division is left. Times the geometric mean of the corners' w it
 * stays between the square roots of their ratio and its inverse (the corners are scaled to
 * at most 1, |s_i| <= 2), which keeps the weights' products in float range up to ratios of
 * about a million; where the driver clips it is interpolated with perspective, at most 2. A non-planar quad keeps
 * the screen cover and g_i, and the fragment shader intersects its ray with the bilinear patch
 * of the corners (the exact reference's surface), weighs the hit's projection onto the
 * best-fit plane and writes the hit's depth.
 * Fragment shader: the core's robust weights in float (tangent of half angles in the
 * non-cancelling form, the limits on corners and on edge segments), then everything the
 * driver interpolates is interpolated with them (colours after lighting, both faces' colours
 * picked by gl_FrontFacing, texture coordinates after texgen and matrix, fog coordinate), and
 * the fragment stages follow as fixed function orders them: texture environments unit by unit
 * (MODULATE, REPLACE, DECAL, BLEND, ADD per base format; COMBINE with its sources, operands
 * and scales), colour sum, fog, and window depth from the screen weights for non-planar quads
 * only. Programs are cached by key (hash, then comparison), 64 at most; failures are cached
 * too, with one logged warning, and the caller falls back to the CPU path. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

/* ---- a string builder ------------------------------------------------------------------------ */

typedef struct sb {
    char *p;
    size_t n, cap;
    int oom;
} sb;

__attribute__((format(printf, 2, 3))) static void put(sb *b, const char *fmt, ...)
{
    if (b->oom)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int len = vsnprintf(b->p ? b->p + b->n : NULL, b->p ? b->cap - b->n : 0, fmt, ap);
        va_end(ap);
        if (len < 0) {
            b->oom = 1;
            return;
        }
        if (b->p && b->n + (size_t)len < b->cap) {
            b->n += (size_t)len;
            return;
        }
        size_t cap = b->cap ? 2 * b->cap : 4096;
        while (cap < b->n + (size_t)len + 1)
            cap *= 2;
        char *q = realloc(b->p, cap);
        if (!q) {
            b->oom = 1;
            return;
        }
        b->p = q;
        b->cap = cap;
    }
}

/* ---- what a key needs ------------------------------------------------------------------------ */

static int lit(const qgl__key *k)
{
    return (k->flags & QGL__KF_LIGHTING) != 0;
}

static int two_sided(const qgl__key *k)
{
    return lit(k) && (k->flags & QGL__KF_TWO_SIDE);
}

static int has_secondary(const qgl__key *k)
{
    return lit(k) ? (k->flags & QGL__KF_SEPARATE_SPEC) != 0 : (k->flags & QGL__KF_COLOR_SUM) != 0;
}

static int gen_uses(const qgl__key *k, int lo, int hi)
{
    for (int u = 0; u < k->nunits; u++)
        for (int c = 0; c < 4; c++)
            if (k->unit[u].target && k->unit[u].gen[c] >= lo && k->unit[u].gen[c] <= hi)
                return 1;
    return 0;
}

static int frag_clip(const qgl__key *k)
{
    return k->clip && (k->flags & QGL__KF_DEPTH);
}

static int needs_normal(const qgl__key *k)
{
    return lit(k) || gen_uses(k, QGL__G_SPHERE, QGL__G_NORMAL);
}

static int needs_eye(const qgl__key *k)
{
    return lit(k) || k->clip || (k->fog && (k->flags & QGL__KF_FOG_DEPTH)) || gen_uses(k, QGL__G_EYE, QGL__G_REFLECT);
}

/* The texture coordinate components each target reads (q divides s, t, r; a cube map's
 * direction needs none): a 2D texture passes three vec4 per quad, not four, and every vec4 a
 * vertex carries costs a SIMD driver copies and setup per vertex. */
static const char *const tex_comps[] = {
    [QGL__T_1D] = "xw", [QGL__T_2D] = "xyw", [QGL__T_3D] = "xyzw", [QGL__T_CUBE] = "xyz", [QGL__T_RECT] = "xyw"};

/* The view-invariant forms (QGL__KF_PLANE): a planar quad's cover in its plane, a non-planar
 * quad's hit on its bilinear patch. */
static int plane_cover(const qgl__key *k)
{
    return (k->flags & QGL__KF_PLANE) && !(k->flags & QGL__KF_DEPTH);
}

static int patch(const qgl__key *k)
{
    return (k->flags & QGL__KF_PLANE) && (k->flags & QGL__KF_DEPTH);
}

int qgl__key_slots(const qgl__key *k)
{
    int per = k->flags & QGL__KF_FLAT ? 1 : 4;
    int colours = per * (1 + has_secondary(k)) * (two_sided(k) ? 2 : 1);
    int n = (patch(k) ? 4 : 2) + colours + (k->fog ? 1 : 0) + (frag_clip(k) ? 4 : 0) + (k->flags & QGL__KF_DEPTH ? 2 : 0);
    for (int u = 0; u < k->nunits; u++)
        n += k->unit[u].target ? (int)strlen(tex_comps[k->unit[u].target]) : 0;
    return n;
}

/* ---- vertex shader --------------------------------------------------------------------------- */

static const char *const material_names[QGL__NMATERIAL] = {"m_fa", "m_fd", "m_fs", "m_fe",
                                                           "m_ba", "m_bd", "m_bs", "m_be", "m_sh"};

/* The material of one face (f: "Front" / "Back"), with per-vertex materials and colour
 * material substituted as the driver does. */
static void vs_material(sb *b, const qgl__key *k, int back)
{
    const char *F = back ? "Back" : "Front";
    const char *p = back ? "m_b" : "m_f";
    put(b, "qgl_mat material_%s() {\n", F);
    if (k->flags & QGL__KF_MATERIAL)
        put(b, "    qgl_mat m = qgl_mat(%se, %sa, %sd, %ss, m_sh.%c);\n", p, p, p, p, back ? 'y' : 'x');
    else
        put(b, "    qgl_mat m = qgl_mat(gl_%sMaterial.emission, gl_%sMaterial.ambient, gl_%sMaterial.diffuse,\n"
               "                        gl_%sMaterial.specular, gl_%sMaterial.shininess);\n", F, F, F, F, F);
    if (k->cm_mode && (k->cm_face & (back ? 2 : 1))) {
        static const char *const field[] = {"", "m.e", "m.a", "m.d", "m.s", "m.a = m.d"};
        put(b, "    %s = gl_Color;\n", field[k->cm_mode]);
    }
    put(b, "    return m;\n}\n");
}

/* One light's contribution, unrolled with its kind known. */
static void vs_light(sb *b, const qgl__key *k, int i)
{
    int pos = (k->light_pos >> i) & 1, spot = (k->light_spot >> i) & 1;
    put(b, "    {\n");
    if (pos) {
        put(b, "        vec3 VP = gl_LightSource[%d].position.xyz / gl_LightSource[%d].position.w - eye;\n", i, i);
        put(b, "        float d = length(VP);\n        VP /= d;\n");
        put(b, "        float att = 1.0 / (gl_LightSource[%d].constantAttenuation + d * (gl_LightSource[%d].linearAttenuation\n"
               "                     + d * gl_LightSource[%d].quadraticAttenuation));\n", i, i, i);
    } else {
        put(b, "        vec3 VP = normalize(gl_LightSource[%d].position.xyz);\n        float att = 1.0;\n", i);
    }
    if (spot)
        put(b, "        float sd = dot(-VP, normalize(gl_LightSource[%d].spotDirection));\n"
               "        att *= sd >= gl_LightSource[%d].spotCosCutoff ? pow(max(sd, 0.0), gl_LightSource[%d].spotExponent) : 0.0;\n",
            i, i, i);
    put(b, "        amb += att * gl_LightSource[%d].ambient.rgb;\n", i);
    put(b, "        float nv = dot(n, VP);\n        if (nv > 0.0) {\n");
    put(b, "            dif += att * nv * gl_LightSource[%d].diffuse.rgb;\n", i);
    put(b, "            float nh = max(dot(n, normalize(VP + V)), 0.0);\n");
    put(b, "            spe += att * (nh > 0.0 ? pow(nh, m.sh) : (m.sh == 0.0 ? 1.0 : 0.0)) * gl_LightSource[%d].specular.rgb;\n", i);
    put(b, "        }\n    }\n");
}

static void vs_lighting(sb *b, const qgl__key *k)
{
    put(b, "struct qgl_mat { vec4 e, a, d, s; float sh; };\n");
    vs_material(b, k, 0);
    if (two_sided(k))
        vs_material(b, k, 1);
    put(b, "void lighting(qgl_mat m, vec3 n, vec3 eye, out vec4 pri, out vec4 sec) {\n");
    put(b, "    vec3 amb = vec3(0.0), dif = vec3(0.0), spe = vec3(0.0);\n");
    put(b, "    vec3 V = %s;\n", k->flags & QGL__KF_LOCAL_VIEWER ? "-normalize(eye)" : "vec3(0.0, 0.0, 1.0)");
    for (int i = 0; i < 8; i++)
        if ((k->lights >> i) & 1)
            vs_light(b, k, i);
    put(b, "    pri = vec4(m.e.rgb + m.a.rgb * gl_LightModel.ambient.rgb + amb * m.a.rgb + dif * m.d.rgb, m.d.a);\n");
    if (k->flags & QGL__KF_SEPARATE_SPEC)
        put(b, "    sec = vec4(clamp(spe * m.s.rgb, 0.0, 1.0), 0.0);\n");
    else
        put(b, "    pri.rgb += spe * m.s.rgb;\n    sec = vec4(0.0);\n");
    put(b, "    pri = clamp(pri, 0.0, 1.0);\n}\n");
}

/* Texture coordinate c (0..3 = s, t, r, q) of unit u after texgen. */
static void vs_texgen(sb *b, int u, int c, int mode)
{
    static const char comp[] = "xyzw", plane[] = "STRQ";
    switch (mode) {
    case QGL__G_OBJECT: put(b, "    t.%c = dot(gl_ObjectPlane%c[%d], gl_Vertex);\n", comp[c], plane[c], u); break;
    case QGL__G_EYE: put(b, "    t.%c = dot(gl_EyePlane%c[%d], eye4);\n", comp[c], plane[c], u); break;
    case QGL__G_SPHERE: put(b, "    t.%c = sphere.%c;\n", comp[c], comp[c]); break;
    case QGL__G_REFLECT: put(b, "    t.%c = refl.%c;\n", comp[c], comp[c]); break;
    case QGL__G_NORMAL: put(b, "    t.%c = n.%c;\n", comp[c], comp[c]); break;
    default: break;
    }
}

static void vs_declarations(sb *b, const qgl__key *k)
{
    put(b, "out vec4 q_pri;\n");
    if (has_secondary(k))
        put(b, "out vec4 q_sec;\n");
    if (two_sided(k))
        put(b, "out vec4 q_bpri;\n%s", has_secondary(k) ? "out vec4 q_bsec;\n" : "");
    if (k->fog)
        put(b, "out float q_fog;\n");
    if (k->clip)
        put(b, "out vec4 q_eye;\n");
    if (k->flags & QGL__KF_PLANE)
        put(b, "out vec4 q_obj;\n");
    for (int u = 0; u < k->nunits; u++)
        if (k->unit[u].target)
            put(b, "out vec4 q_tex%d;\n", u);
    if (lit(k) && (k->flags & QGL__KF_MATERIAL)) {
        for (int i = 0; i < QGL__NMATERIAL - 1; i++)
            put(b, "in vec4 %s;\n", material_names[i]);
        put(b, "in vec2 m_sh;\n");
    }
}

static void vs_source(sb *b, const qgl__key *k)
{
    put(b, "#version 150 compatibility\n");
    vs_declarations(b, k);
    if (lit(k))
        vs_lighting(b, k);
    put(b, "void main() {\n    gl_Position = ftransform();\n");
    if (needs_eye(k))
        put(b, "    vec4 eye4 = gl_ModelViewMatrix * gl_Vertex;\n    vec3 eye = eye4.xyz;\n");
    if (needs_normal(k)) {
        put(b, "    vec3 n = gl_NormalMatrix * gl_Normal;\n");
        if (k->flags & QGL__KF_NORMALIZE)
            put(b, "    n = normalize(n);\n");
        else if (k->flags & QGL__KF_RESCALE)
            put(b, "    n *= gl_NormalScale;\n");
    }
    if (lit(k)) {
        put(b, "    vec4 sec;\n    lighting(material_Front(), n, eye, q_pri, sec);\n");
        if (has_secondary(k))
            put(b, "    q_sec = sec;\n");
        if (two_sided(k))
            put(b, "    lighting(material_Back(), -n, eye, q_bpri, sec);\n");
        if (two_sided(k) && has_secondary(k))
            put(b, "    q_bsec = sec;\n");
    } else {
        put(b, "    q_pri = clamp(gl_Color, 0.0, 1.0);\n");
        if (has_secondary(k))
            put(b, "    q_sec = vec4(clamp(gl_SecondaryColor.rgb, 0.0, 1.0), 0.0);\n");
    }
    if (k->fog)
        put(b, "    q_fog = %s;\n", k->flags & QGL__KF_FOG_DEPTH ? "abs(eye4.z)" : "gl_FogCoord");
    if (k->clip)
        put(b, "    q_eye = eye4;\n");
    if (k->flags & QGL__KF_PLANE)
        put(b, "    q_obj = gl_Vertex;\n");
    if (gen_uses(k, QGL__G_SPHERE, QGL__G_REFLECT)) {
        put(b, "    vec3 refl = reflect(normalize(eye), n);\n");
        put(b, "    float sm = 2.0 * sqrt(refl.x * refl.x + refl.y * refl.y + (refl.z + 1.0) * (refl.z + 1.0));\n");
        put(b, "    vec2 sphere = refl.xy / sm + 0.5;\n");
    }
    for (int u = 0; u < k->nunits; u++) {
        if (!k->unit[u].target)
            continue;
        put(b, "    {\n    vec4 t = gl_MultiTexCoord%d;\n", u);
        for (int c = 0; c < 4; c++)
            vs_texgen(b, u, c, k->unit[u].gen[c]);
        put(b, "    q_tex%d = gl_TextureMatrix[%d] * t;\n    }\n", u, u);
    }
    put(b, "}\n");
}

/* ---- geometry shader ------------------------------------------------------------------------- */

/* The flat per-corner values: name, GLSL type when smooth and whether flat shading applies. */
typedef struct flat_var {
    const char *name;
    int colour; /* flat shading passes only the provoking corner's value */
    int scalar; /* float per corner (packed into one vec4) */
    const char *comps; /* only these components, one vec4 of the four corners' values each */
} flat_var;

static int flat_vars(const qgl__key *k, flat_var out[16])
{
    int n = 0;
    out[n++] = (flat_var){"pri", 1, 0, NULL};
    if (has_secondary(k))
        out[n++] = (flat_var){"sec", 1, 0, NULL};
    if (two_sided(k)) {
        out[n++] = (flat_var){"bpri", 1, 0, NULL};
        if (has_secondary(k))
            out[n++] = (flat_var){"bsec", 1, 0, NULL};
    }
    if (k->fog)
        out[n++] = (flat_var){"fog", 0, 1, NULL};
    if (frag_clip(k))
        out[n++] = (flat_var){"eye", 0, 0, NULL};
    static const char *const tex[QGL_MAX_TEXUNITS] = {"tex0", "tex1", "tex2", "tex3"};
    for (int u = 0; u < k->nunits; u++)
        if (k->unit[u].target)
            out[n++] = (flat_var){tex[u], 0, 0, tex_comps[k->unit[u].target]};
    return n;
}

static const char *flat_type(const qgl__key *k, const flat_var *v)
{
    static const char *const rows[] = {"", "vec4", "mat2x4", "mat3x4", "mat4"};
    if (v->colour && (k->flags & QGL__KF_FLAT))
        return "vec4";
    if (v->comps)
        return rows[strlen(v->comps)];
    return v->scalar ? "vec4" : "mat4";
}

/* g_i / W is affine in the window: interpolated without perspective and scaled per quad (see
 * the geometry shader) it reaches the weights as it is. Where the driver clips (a corner
 * outside the view volume, clip planes), g_i stays linear in clip space, perspective-
 * interpolated and normalised per fragment: clippers compute perspective attributes of new
 * vertices in clip space, exactly, but noperspective ones from a screen-space parameter that
 * Mesa takes along x even when the edge is nearly vertical on screen (measured: colours off
 * by up to 115 levels on a floor reaching past the window). */
static int persp(const qgl__key *k)
{
    return (k->flags & QGL__KF_CLIPPED) || k->clip;
}

static void varyings(sb *b, const qgl__key *k, const char *dir)
{
    flat_var v[16];
    int n = flat_vars(k, v);
    put(b, "%s%s vec4 gA, gB;\n", persp(k) ? "" : "noperspective ", dir);
    if (patch(k))
        put(b, "flat %s vec4 f_qx, f_qy;\n", dir);
    for (int i = 0; i < n; i++)
        put(b, "flat %s %s f_%s;\n", dir, flat_type(k, &v[i]), v[i].name);
    if (k->flags & QGL__KF_DEPTH)
        put(b, "flat %s vec4 f_w, f_z;\n", dir);
}

/* The quad's plane frame from its object corners (core plane.c in float): origin at the
 * centroid, normal the longest of the diagonals' cross product and the corner normals, first
 * axis along the longer diagonal; Q[i] the corners' in-plane coordinates scaled to at most 1
 * (the weights' products stay in float range and the weights do not change). A corner at infinity in object space (w <= 0) makes NDC stand in for the object
 * positions: a valid picture, as view-dependent as the screen-space weights. False when the
 * corners span no plane. */
static const char gs_plane[] =
    "bool plane_frame() {\n"
    "    vec3 d[4], o = vec3(0.0);\n"
    /* a corner at infinity in object space: NDC stands in (planar alike, but not rigid) */
    "    bool finite = all(greaterThan(vec4(q_obj[0].w, q_obj[1].w, q_obj[2].w, q_obj[3].w), vec4(0.0)));\n"
    "    for (int i = 0; i < 4; i++) {\n"
    "        vec4 h = finite ? q_obj[i] : C[i];\n"
    "        if (!(h.w > 0.0)) return false;\n"
    "        d[i] = h.xyz / h.w;\n"
    "        o += d[i];\n"
    "    }\n"
    "    o *= 0.25;\n"
    "    float m = 0.0;\n"
    "    for (int i = 0; i < 4; i++) { d[i] -= o; m = max(m, max(max(abs(d[i].x), abs(d[i].y)), abs(d[i].z))); }\n"
    "    if (!(m > 0.0)) return false;\n"
    "    for (int i = 0; i < 4; i++) d[i] /= m;\n"
    "    vec3 a = d[2] - d[0], b = d[3] - d[1], n = cross(a, b);\n"
    "    float best = dot(n, n);\n"
    "    for (int i = 0; i < 4; i++) {\n"
    "        vec3 c = cross(d[(i + 1) & 3] - d[i], d[(i + 3) & 3] - d[i]);\n"
    "        if (dot(c, c) > best) { best = dot(c, c); n = c; }\n"
    "    }\n"
    "    if (!(best > 1e-24)) return false;\n"
    "    n *= inversesqrt(best);\n"
    "    vec3 g = dot(a, a) >= dot(b, b) ? a : b;\n"
    "    vec3 u = normalize(g - dot(g, n) * n), v = cross(n, u);\n"
    "    float r = 0.0;\n"
    "    for (int i = 0; i < 4; i++) { Q[i] = vec2(dot(d[i], u), dot(d[i], v)); r = max(r, max(abs(Q[i].x), abs(Q[i].y))); }\n"
    "    for (int i = 0; i < 4; i++) Q[i] /= r;\n"
    "    c_qx = vec4(Q[0].x, Q[1].x, Q[2].x, Q[3].x);\n"
    "    c_qy = vec4(Q[0].y, Q[1].y, Q[2].y, Q[3].y);\n"
    "    return true;\n"
    "}\n";

/* The cover of the 2D quad v (the screen quad, or the quad in its plane): convex along the
 * diagonal 1-3 (triangles 0-1-3, 1-2-3, as llvmpipe splits GL_QUADS in display lists, under
 * the first-vertex convention and in any draw that clips: the same boundary pixels there; an
 * unclipped immediate draw takes 0-2, decided per driver batch, which no cover can follow),
 * concave through the reflex corner, a bow-tie as its two lobes. */
static const char gs_cover[] =
    /* the cover found: none (0), a strip of triangles (a, a+1, a+2) and (a, a+2, a+3), four
     * vertices (1), or a bow-tie's two lobes meeting at the crossing C[4] on edge a, a+1 (2) */
    "int c_mode = 0, c_a = 1;\n"
    "void quad(int a) { c_mode = 1; c_a = a; }\n"
    "float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }\n"
    /* C[4] (its eye and in-plane positions) := the crossing point, at parameter t along
     * a->b in the plane it was found in: on screen, made perspective-correct with the clip w;
     * in the plane, affine, made homogeneous with the object w (clip and eye positions are
     * linear in the homogeneous object position) */
    "void set_cross(int a, int b, float t) {\n"
    "#if PLANE_COVER\n"
    "    float wa = q_obj[a].w, wb = q_obj[b].w;\n"
    "    Q[4] = mix(Q[a], Q[b], t);\n"
    "#else\n"
    "    float wa = C[a].w, wb = C[b].w;\n"
    "#endif\n"
    "    float s = t * wa / ((1.0 - t) * wb + t * wa);\n"
    "    C[4] = mix(C[a], C[b], s);\n"
    "#if CLIP\n"
    "    E[4] = mix(E[a], E[b], s);\n"
    "#endif\n"
    "}\n"
    /* parameters (t on a->b, u on c->d) of the crossing of two segments */
    "vec2 crossing(vec2 a, vec2 b, vec2 c, vec2 d) {\n"
    "    float den = cross2(b - a, d - c);\n"
    "    if (den == 0.0) return vec2(-1.0);\n"
    "    return vec2(cross2(c - a, d - c), cross2(c - a, b - a)) / den;\n"
    "}\n"
    "bool inside01(vec2 tu) { return all(greaterThanEqual(tu, vec2(0.0))) && all(lessThanEqual(tu, vec2(1.0))); }\n"
    "void cover(vec2 v[4]) {\n"
    "    int npos = 0, nneg = 0, ipos = 0, ineg = 0;\n"
    "    for (int i = 0; i < 4; i++) {\n"
    "        float k = cross2(v[i] - v[(i + 3) & 3], v[(i + 1) & 3] - v[i]);\n"
    "        if (k > 0.0) { npos++; ipos = i; }\n"
    "        if (k < 0.0) { nneg++; ineg = i; }\n"
    "    }\n"
    "    if (npos + nneg == 0) return;\n"
    "    if (npos == 0 || nneg == 0) { quad(1); return; }\n"
    "    if (npos != nneg) {\n"
    "        quad(npos < nneg ? ipos : ineg);\n"
    "        return;\n"
    "    }\n"
    "    vec2 tu = crossing(v[0], v[1], v[2], v[3]);\n"
    "    if (inside01(tu)) {\n"
    "        set_cross(0, 1, tu.x);\n"
    "        c_mode = 2; c_a = 0;\n"
    "        return;\n"
    "    }\n"
    "    tu = crossing(v[1], v[2], v[3], v[0]);\n"
    "    if (inside01(tu)) {\n"
    "        set_cross(1, 2, tu.x);\n"
    "        c_mode = 2; c_a = 1;\n"
    "        return;\n"
    "    }\n"
    "    quad(1);\n"
    "}\n"
    "void find_cover() {\n"
    "    for (int i = 0; i < 4; i++) C[i] = gl_in[i].gl_Position;\n"
    "#if CLIP\n"
    "    for (int i = 0; i < 4; i++) E[i] = q_eye[i];\n"
    "#endif\n"
    "    corners();\n"
    "#if PLANE\n"
    "    if (!plane_frame()) return;\n"
    "#endif\n"
    "    vec4 w = vec4(C[0].w, C[1].w, C[2].w, C[3].w);\n"
    /* in the plane the cover is exact whatever the camera: the clipper cuts it */
    "#if PLANE_COVER\n"
    "    if (all(lessThanEqual(w, vec4(0.0)))) return;\n"
    "#if !PERSP\n"
    "    w_mean = sqrt(min(min(w.x, w.y), min(w.z, w.w)) * max(max(w.x, w.y), max(w.z, w.w)));\n"
    "#endif\n"
    "    vec2 q[4] = vec2[4](Q[0], Q[1], Q[2], Q[3]);\n"
    "    cover(q);\n"
    "#else\n"
    /* a corner behind the eye: the driver's own split, 0-1-3 and 1-2-3 (the other diagonal's
     * triangles, clipped, can leave out much of the quad: test_edge) */
    "    if (any(lessThanEqual(w, vec4(0.0)))) {\n"
    "        if (all(lessThanEqual(w, vec4(0.0)))) return;\n"
    "        quad(1);\n"
    "        return;\n"
    "    }\n"
    "    vec2 v[4];\n"
    "    for (int i = 0; i < 4; i++) v[i] = C[i].xy / C[i].w;\n"
    /* A fragment p lies in the quad's bounding box and in the viewport, so |g_i| = w_i |v_i -
     * p| px is at most w_i times v_i's L1 distance (in pixels) to the farthest point of that
     * box. Dividing by the largest such bound keeps every g_i <= 1 and, the bound being
     * nearly reached, the weights' products (degree 11) in float range; a per-fragment
     * normalisation did that before. Taking w_i and the distance per corner matters for a
     * floor to the horizon: far corners have large w but lie close, near ones the reverse. */
    "#if !PERSP\n"
    "    vec2 lo = max(min(min(v[0], v[1]), min(v[2], v[3])), vec2(-1.0));\n"
    "    vec2 hi = min(max(max(v[0], v[1]), max(v[2], v[3])), vec2(1.0));\n"
    "    float bound = 0.0;\n"
    "    for (int i = 0; i < 4; i++) bound = max(bound, w[i] * dot(max(v[i] - lo, hi - v[i]), u_px));\n"
    "    g_scale = u_px.xyxy / max(bound, 1e-30);\n"
    "#endif\n"
    "    cover(v);\n"
    "#endif\n"
    "}\n"
    /* One emission for every case, the lobes' first four vertices in the strip's slots: a SIMD
     * driver (llvmpipe) runs every branch's emits for all its primitives, masked, so emits
     * spread over the cases cost several times over. */
    "void main() {\n"
    "    find_cover();\n"
    "    if (c_mode == 0) return;\n"
    "    int a = c_a, b = (a + 1) & 3, c = (a + 2) & 3, d = (a + 3) & 3;\n"
    "    bool q = c_mode == 1;\n"
    "    emit(q ? b : 4); emit(q ? c : b); emit(q ? a : c);\n"
    "    if (!q) EndPrimitive();\n"
    "    emit(q ? d : 4);\n"
    "    if (!q) { emit(d); emit(a); }\n"
    "    EndPrimitive();\n"
    "}\n";

static void gs_source(sb *b, const qgl__key *k)
{
    flat_var v[16];
    int n = flat_vars(k, v);
    int hw_clip = k->clip && !frag_clip(k);
    put(b, "#version 150 compatibility\n#define CLIP %d\n#define PERSP %d\n#define PLANE %d\n#define PLANE_COVER %d\n",
        k->clip ? 1 : 0, persp(k), (k->flags & QGL__KF_PLANE) != 0, plane_cover(k));
    put(b, "layout(lines_adjacency) in;\nlayout(triangle_strip, max_vertices = 6) out;\n");
    for (int i = 0; i < n; i++)
        put(b, "in %s q_%s[];\n", v[i].scalar ? "float" : "vec4", v[i].name);
    if (k->clip && !frag_clip(k))
        put(b, "in vec4 q_eye[];\n");
    if (k->flags & QGL__KF_PLANE)
        put(b, "in vec4 q_obj[];\nvec2 Q[5];\nvec4 c_qx, c_qy;\nfloat w_mean;\n");
    varyings(b, k, "out");
    put(b, "uniform vec2 u_px;\nvec4 C[5];\nvec4 g_scale;\n");
    if (k->clip)
        put(b, "vec4 E[5];\n");
    /* the flat values are the same for every emitted vertex: gathered once */
    for (int i = 0; i < n; i++)
        put(b, "%s c_%s;\n", flat_type(k, &v[i]), v[i].name);
    if (k->flags & QGL__KF_DEPTH)
        put(b, "vec4 c_w, c_z;\n");
    put(b, "void corners() {\n");
    for (int i = 0; i < n; i++) {
        const char *nm = v[i].name;
        if (v[i].colour && (k->flags & QGL__KF_FLAT))
            put(b, "    c_%s = q_%s[%d];\n", nm, nm, k->corner);
        else if (v[i].scalar)
            put(b, "    c_%s = vec4(q_%s[0], q_%s[1], q_%s[2], q_%s[3]);\n", nm, nm, nm, nm, nm);
        else if (v[i].comps) {
            put(b, "    c_%s = %s(", nm, flat_type(k, &v[i]));
            for (const char *c = v[i].comps; *c; c++)
                put(b, "%svec4(q_%s[0].%c, q_%s[1].%c, q_%s[2].%c, q_%s[3].%c)", c == v[i].comps ? "" : ", ", nm, *c, nm,
                    *c, nm, *c, nm, *c);
            put(b, ");\n");
        }
        else
            put(b, "    c_%s = mat4(q_%s[0], q_%s[1], q_%s[2], q_%s[3]);\n", nm, nm, nm, nm, nm);
    }
    if (k->flags & QGL__KF_DEPTH)
        put(b, "    c_w = vec4(C[0].w, C[1].w, C[2].w, C[3].w);\n"
               "    c_z = (vec4(C[0].z / C[0].w, C[1].z / C[1].w, C[2].z / C[2].w, C[3].z / C[3].w)\n"
               "           * gl_DepthRange.diff + (gl_DepthRange.near + gl_DepthRange.far)) * 0.5;\n");
    put(b, "}\n");
    put(b, "void emit(int k) {\n    vec4 X = C[k];\n    gl_Position = X;\n");
    if (patch(k))
        put(b, "    f_qx = c_qx;\n    f_qy = c_qy;\n");
    if (plane_cover(k)) {
        put(b, "    float h = %s;\n", persp(k) ? "1.0" : "w_mean / X.w");
        put(b, "    gA = vec4(Q[0] - Q[k], Q[1] - Q[k]) * h;\n    gB = vec4(Q[2] - Q[k], Q[3] - Q[k]) * h;\n");
    } else if (persp(k)) {
        put(b, "    gA = vec4(C[0].xy * X.w - X.xy * C[0].w, C[1].xy * X.w - X.xy * C[1].w) * u_px.xyxy;\n");
        put(b, "    gB = vec4(C[2].xy * X.w - X.xy * C[2].w, C[3].xy * X.w - X.xy * C[3].w) * u_px.xyxy;\n");
    } else {
        put(b, "    vec2 n = X.xy / X.w;\n");
        put(b, "    gA = vec4(C[0].xy - n * C[0].w, C[1].xy - n * C[1].w) * g_scale;\n");
        put(b, "    gB = vec4(C[2].xy - n * C[2].w, C[3].xy - n * C[3].w) * g_scale;\n");
    }
    for (int p = 0; p < 8; p++)
        if ((k->clip >> p) & 1)
            {
            if (hw_clip)
                put(b, "    gl_ClipDistance[%d] = dot(gl_ClipPlane[%d], E[k]);\n", p, p);
            else
                put(b, "    gl_ClipDistance[%d] = 1.0;\n", p);
        }
    for (int i = 0; i < n; i++)
        put(b, "    f_%s = c_%s;\n", v[i].name, v[i].name);
    if (k->flags & QGL__KF_DEPTH)
        put(b, "    f_w = c_w;\n    f_z = c_z;\n");
    put(b, "    EmitVertex();\n}\n");
    if (k->flags & QGL__KF_PLANE)
        put(b, "%s", gs_plane);
    put(b, "%s", gs_cover);
}

/* ---- fragment shader ------------------------------------------------------------------------- */

/* The core's weights (libquadgl/core/weights_impl.h) in float, four corners at once, shared
 * by both shader paths (GLSL 1.20 has no select by bvec: mix by a 0/1 vector there, exact
 * since both candidates are finite). sx, sy are the corners' g_i, a positive multiple of the
 * core's s~_i. One division instead of nine: t_i = num_i / den_i (the non-cancelling form)
 * and nu_i = (t_{i-1} + t_i) / r_i are scaled by the common factor prod_j den_j r_j, which
 * leaves only products. On an edge segment (den_i = 0) this gives the edge's linear
 * interpolation as the limit, with no test. On a corner (r_i = 0) every product holds r_i or
 * a den that vanishes with it, so all nu are 0 and adding 1 to nu_i gives the corner's own
 * value; a branch would cost as much, since SIMD rasterizers run both sides. The products
 * (degree 11 in g) stay in float range for |g_i| up to about 1 and not far below: the
 * geometry shader scales g per quad so; quad_weights_any scales them per fragment. */
const char qgl__glsl_weights[] =
    "#if __VERSION__ >= 130\n"
    "#define QGL_SELECT(a, b, c) mix(a, b, c)\n"
    "#else\n"
    "#define QGL_SELECT(a, b, c) mix(a, b, vec4(c))\n"
    "#endif\n"
    "vec4 quad_weights(vec4 sx, vec4 sy) {\n"
    "    vec4 sxn = sx.yzwx, syn = sy.yzwx;\n"
    "    vec4 rho = sqrt(sx * sx + sy * sy);\n"
    "    vec4 A = sx * syn - sy * sxn;\n"
    "    vec4 D = sx * sxn + sy * syn;\n"
    "    vec4 P = rho * rho.yzwx;\n"
    "    bvec4 pd = greaterThan(D, vec4(0.0));\n"
    "    vec4 num = QGL_SELECT(P - D, A, pd), den = QGL_SELECT(A, P + D, pd);\n"
    "    vec4 nu = (num.wxyz * den + num * den.wxyz) * (den.yzwx * den.zwxy) * (P.yzwx * rho.wxyz);\n"
    "    nu += vec4(equal(rho, vec4(0.0)));\n"
    "    return nu * (1.0 / dot(nu, vec4(1.0)));\n"
    "}\n"
    /* g of any size: scaled to a sum of 1 first */
    "vec4 quad_weights_any(vec4 sx, vec4 sy) {\n"
    "    float k = 1.0 / dot(abs(sx) + abs(sy), vec4(1.0));\n"
    "    return quad_weights(sx * k, sy * k);\n"
    "}\n";

/* The hit of the fragment's ray on the bilinear patch of the corners (the exact reference's
 * construction, sw_exact.c, in float): with the corners' s~ (sx, sy; any common positive
 * scale), the patch point's bilinear combination of them vanishes, which leaves a quadratic
 * in v, solved in the cancellation-free form (both roots from q = -(k1 + sign(k1) sqrt(disc))
 * / 2; as the patch flattens one runs off to infinity and the other tends to the linear
 * root), u by least squares along the v-line. Of the roots within the square (a small
 * margin for rounding) the nearer one wins; with none, the one nearer the square, clamped.
 * Returns the hit's bilinear weights; depth receives its window depth from the corners' clip
 * w and window depths z. */
const char qgl__glsl_patch[] =
    "float qgl_cross(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }\n"
    "vec4 qgl_bilinear(vec2 uv) {\n"
    "    uv = clamp(uv, 0.0, 1.0);\n"
    "    return vec4((1.0 - uv.x) * (1.0 - uv.y), uv.x * (1.0 - uv.y), uv.x * uv.y, (1.0 - uv.x) * uv.y);\n"
    "}\n"
    "vec2 qgl_root(vec2 s0, vec2 e1, vec2 e3, vec2 g, float v) {\n"
    "    vec2 d = e1 + v * g, n = s0 + v * e3;\n"
    "    return vec2(-dot(n, d) / dot(d, d), v);\n"
    "}\n"
    "float qgl_outside(vec2 uv) {\n"
    "    vec2 o = max(-uv, uv - 1.0);\n"
    "    float m = max(o.x, o.y);\n"
    "    return m == m ? m : 1e30;\n"
    "}\n"
    "vec4 patch_hit(vec4 sx, vec4 sy, vec4 w, vec4 z, out float depth) {\n"
    "    vec2 s0 = vec2(sx.x, sy.x), e1 = vec2(sx.y, sy.y) - s0, e3 = vec2(sx.w, sy.w) - s0;\n"
    "    vec2 g = vec2(sx.x - sx.y + sx.z - sx.w, sy.x - sy.y + sy.z - sy.w);\n"
    "    float k2 = qgl_cross(e3, g), k1 = qgl_cross(s0, g) + qgl_cross(e3, e1), k0 = qgl_cross(s0, e1);\n"
    "    float q = -0.5 * (k1 + (k1 < 0.0 ? -1.0 : 1.0) * sqrt(max(k1 * k1 - 4.0 * k2 * k0, 0.0)));\n"
    "    vec2 a = qgl_root(s0, e1, e3, g, k0 / q);\n"
    "    float oa = qgl_outside(a), vb = q / k2;\n"
    /* the other root's v off the square (it runs off to infinity as the patch flattens): its
     * hit cannot be taken, and the first alone decides (what the full test below gives) */
    "    if (oa <= 1e-3 && !(vb >= -1e-3 && vb <= 1.001)) {\n"
    "        vec4 ba = qgl_bilinear(a) * w;\n"
    "        depth = dot(ba, z) / dot(ba, vec4(1.0));\n"
    "        return qgl_bilinear(a);\n"
    "    }\n"
    "    vec2 b = qgl_root(s0, e1, e3, g, vb);\n"
    "    float ob = qgl_outside(b);\n"
    "    vec4 ba = qgl_bilinear(a) * w, bb = qgl_bilinear(b) * w;\n"
    /* the nearer of two hits by cross-multiplied depths (the w sums are positive) */
    "    float na = dot(ba, z), da = dot(ba, vec4(1.0)), nb = dot(bb, z), db = dot(bb, vec4(1.0));\n"
    "    bool in_a = oa <= 1e-3, in_b = ob <= 1e-3;\n"
    "    bool take_b = in_b ? (!in_a || nb * da < na * db) : (!in_a && ob < oa);\n"
    "    depth = take_b ? nb / db : na / da;\n"
    "    return qgl_bilinear(take_b ? b : a);\n"
    "}\n";

static const char fs_weights[] =
    "vec4 weights() {\n"
    "    return QGL_WEIGHTS(vec4(gA.x, gA.z, gB.x, gB.z), vec4(gA.y, gA.w, gB.y, gB.w));\n"
    "}\n";

/* The patch form: the hit's projection onto the plane, weighed there (the hit's depth and
 * bilinear weights are kept for gl_FragDepth and clip planes). */
static const char fs_weights_patch[] =
    "float patch_depth;\n"
    "vec4 patch_b;\n"
    "vec4 weights() {\n"
    "    vec4 sx = vec4(gA.x, gA.z, gB.x, gB.z), sy = vec4(gA.y, gA.w, gB.y, gB.w);\n"
    "#if PERSP\n"
    "    float k = 1.0 / dot(abs(sx) + abs(sy), vec4(1.0));\n"
    "    sx *= k;\n"
    "    sy *= k;\n"
    "#endif\n"
    "    patch_b = patch_hit(sx, sy, f_w, f_z, patch_depth);\n"
    "    return quad_weights(f_qx - dot(patch_b, f_qx), f_qy - dot(patch_b, f_qy));\n"
    "}\n";

static const char *const sampler_type[] = {"", "sampler1D", "sampler2D", "sampler3D", "samplerCube", "sampler2DRect"};

/* The texel of unit u (texture coordinates interpolated, divided by q as fixed function). */
static void fs_texel(sb *b, const qgl__key *k, int u)
{
    /* lam times the rows: the components the target reads (tex_comps), interpolated */
    put(b, "    vec%zu tc%d = lam * f_tex%d;\n", strlen(tex_comps[k->unit[u].target]), u, u);
    put(b, "    vec4 tx%d = %s(u_tex%d, tc%d);\n", u, k->unit[u].target == QGL__T_CUBE ? "texture" : "textureProj", u, u);
}

/* A COMBINE source as a vec4 expression. */
static void src_expr(char *out, size_t n, int u, int src)
{
    switch (src) {
    case QGL__S_TEXTURE: snprintf(out, n, "tx%d", u); break;
    case QGL__S_CONSTANT: snprintf(out, n, "gl_TextureEnvColor[%d]", u); break;
    case QGL__S_PRIMARY: snprintf(out, n, "pri"); break;
    case QGL__S_PREVIOUS: snprintf(out, n, "col"); break;
    default: snprintf(out, n, "tx%d", src - QGL__S_UNIT0); break;
    }
}

static int nargs(int func)
{
    if (func == QGL__C_REPLACE)
        return 1;
    return func == QGL__C_INTERPOLATE ? 3 : 2;
}

static void fs_combine_func(sb *b, int func, const char *t, const char *res)
{
    switch (func) {
    case QGL__C_REPLACE: put(b, "        %s = %s0;\n", res, t); break;
    case QGL__C_MODULATE: put(b, "        %s = %s0 * %s1;\n", res, t, t); break;
    case QGL__C_ADD: put(b, "        %s = %s0 + %s1;\n", res, t, t); break;
    case QGL__C_ADD_SIGNED: put(b, "        %s = %s0 + %s1 - 0.5;\n", res, t, t); break;
    case QGL__C_INTERPOLATE: put(b, "        %s = %s0 * %s2 + %s1 * (1.0 - %s2);\n", res, t, t, t, t); break;
    case QGL__C_SUBTRACT: put(b, "        %s = %s0 - %s1;\n", res, t, t); break;
    default: put(b, "        %s = vec3(4.0 * dot(%s0 - 0.5, %s1 - 0.5));\n", res, t, t); break;
    }
}

static void fs_combine(sb *b, const qgl__unit_key *uk, int u)
{
    static const char *const op_rgb[] = {"%s.rgb", "(1.0 - %s.rgb)", "vec3(%s.a)", "vec3(1.0 - %s.a)"};
    static const char *const op_a[] = {"%s.a", "(1.0 - %s.a)", "%s.a", "(1.0 - %s.a)"};
    char src[64], expr[128];
    int dot4 = uk->func_rgb == QGL__C_DOT3_RGBA;
    put(b, "    {\n        vec3 rgb;\n        float a;\n");
    for (int i = 0; i < nargs(uk->func_rgb); i++) {
        src_expr(src, sizeof src, u, uk->src_rgb[i]);
        snprintf(expr, sizeof expr, op_rgb[uk->op_rgb[i]], src);
        put(b, "        vec3 c%d = %s;\n", i, expr);
    }
    fs_combine_func(b, uk->func_rgb, "c", "rgb");
    if (dot4) {
        put(b, "        a = rgb.r;\n");
    } else {
        for (int i = 0; i < nargs(uk->func_a); i++) {
            src_expr(src, sizeof src, u, uk->src_a[i]);
            snprintf(expr, sizeof expr, op_a[uk->op_a[i]], src);
            put(b, "        float a%d = %s;\n", i, expr);
        }
        /* the alpha functions are the RGB ones on one component */
        switch (uk->func_a) {
        case QGL__C_REPLACE: put(b, "        a = a0;\n"); break;
        case QGL__C_MODULATE: put(b, "        a = a0 * a1;\n"); break;
        case QGL__C_ADD: put(b, "        a = a0 + a1;\n"); break;
        case QGL__C_ADD_SIGNED: put(b, "        a = a0 + a1 - 0.5;\n"); break;
        case QGL__C_INTERPOLATE: put(b, "        a = a0 * a2 + a1 * (1.0 - a2);\n"); break;
        default: put(b, "        a = a0 - a1;\n"); break;
        }
    }
    put(b, "        col = clamp(vec4(rgb * %d.0, a * %d.0), 0.0, 1.0);\n    }\n", 1 << uk->shift_rgb,
        1 << (dot4 ? uk->shift_rgb : uk->shift_a));
}

/* One unit's texture environment: col (previous) := f(col, tx_u), per base format. */
static void fs_env(sb *b, const qgl__unit_key *uk, int u)
{
    int fmt = uk->format;
    if (uk->env == QGL__E_COMBINE) {
        fs_combine(b, uk, u);
        return;
    }
    if (fmt == QGL__F_ALPHA) { /* the colour passes; alpha is replaced or multiplied */
        if (uk->env == QGL__E_REPLACE)
            put(b, "    col.a = tx%d.a;\n", u);
        else if (uk->env != QGL__E_DECAL)
            put(b, "    col.a *= tx%d.a;\n", u);
        return;
    }
    switch (uk->env) {
    case QGL__E_REPLACE:
        if (fmt == QGL__F_RGB)
            put(b, "    col.rgb = tx%d.rgb;\n", u);
        else
            put(b, "    col = tx%d;\n", u);
        break;
    case QGL__E_MODULATE: put(b, "    col *= tx%d;\n", u); break;
    case QGL__E_DECAL: put(b, "    col.rgb = mix(col.rgb, tx%d.rgb, tx%d.a);\n", u, u); break;
    case QGL__E_BLEND:
        put(b, "    col.rgb = mix(col.rgb, gl_TextureEnvColor[%d].rgb, tx%d.rgb);\n", u, u);
        if (fmt == QGL__F_INTENSITY)
            put(b, "    col.a = mix(col.a, gl_TextureEnvColor[%d].a, tx%d.a);\n", u, u);
        else
            put(b, "    col.a *= tx%d.a;\n", u);
        break;
    default: /* ADD */
        put(b, "    col.rgb += tx%d.rgb;\n", u);
        if (fmt == QGL__F_INTENSITY)
            put(b, "    col.a += tx%d.a;\n", u);
        else
            put(b, "    col.a *= tx%d.a;\n", u);
        break;
    }
    put(b, "    col = clamp(col, 0.0, 1.0);\n");
}

static void fs_fog(sb *b, const qgl__key *k)
{
    put(b, "    float fc = dot(f_fog, lam);\n");
    switch (k->fog) {
    case QGL__FOG_LINEAR: put(b, "    float ff = (gl_Fog.end - fc) * gl_Fog.scale;\n"); break;
    case QGL__FOG_EXP: put(b, "    float ff = exp(-gl_Fog.density * fc);\n"); break;
    default: put(b, "    float ff = exp(-(gl_Fog.density * fc) * (gl_Fog.density * fc));\n"); break;
    }
    put(b, "    col.rgb = mix(gl_Fog.color.rgb, col.rgb, clamp(ff, 0.0, 1.0));\n");
}

/* A colour at the fragment: the provoking corner's (flat) or interpolated. */
static void fs_colour(sb *b, const qgl__key *k, const char *name, const char *front, const char *back)
{
    const char *fmt = k->flags & QGL__KF_FLAT ? "f_%s" : "(f_%s * lam)";
    char f[32], bk[32];
    snprintf(f, sizeof f, fmt, front);
    if (!two_sided(k)) {
        put(b, "    vec4 %s = %s;\n", name, f);
        return;
    }
    snprintf(bk, sizeof bk, fmt, back);
    put(b, "    vec4 %s = gl_FrontFacing ? %s : %s;\n", name, f, bk);
}

static void fs_source(sb *b, const qgl__key *k)
{
    put(b, "#version 150 compatibility\n#define PERSP %d\n", persp(k));
    varyings(b, k, "in");
    for (int u = 0; u < k->nunits; u++)
        if (k->unit[u].target)
            put(b, "uniform %s u_tex%d;\n", sampler_type[k->unit[u].target], u);
    /* in-plane s_i are bounded by the quad's scaled size: no normalisation */
    put(b, "#define QGL_WEIGHTS %s\n", persp(k) && !plane_cover(k) ? "quad_weights_any" : "quad_weights");
    put(b, "%s", qgl__glsl_weights);
    if (patch(k))
        put(b, "%s%s", qgl__glsl_patch, fs_weights_patch);
    else
        put(b, "%s", fs_weights);
    put(b, "void main() {\n    vec4 lam = weights();\n");
    /* the cover in the plane is exact: nothing of it lies outside the quad */
    if ((k->flags & QGL__KF_DISCARD) && !plane_cover(k))
        put(b, "    if (any(lessThan(lam, vec4(-1e-5)))) discard;\n");
    if (frag_clip(k)) {
        /* the in-plane weights reproduce the projection only: the patch point's own */
        put(b, "    vec4 eye = f_eye * %s;\n", patch(k) ? "patch_b" : "lam");
        for (int p = 0; p < 8; p++)
            if ((k->clip >> p) & 1)
                put(b, "    if (dot(gl_ClipPlane[%d], eye) < 0.0) discard;\n", p);
    }
    fs_colour(b, k, "pri", "pri", "bpri");
    if (has_secondary(k))
        fs_colour(b, k, "sec", "sec", "bsec");
    put(b, "    vec4 col = pri;\n");
    for (int u = 0; u < k->nunits; u++)
        if (k->unit[u].target)
            fs_texel(b, k, u);
    for (int u = 0; u < k->nunits; u++)
        if (k->unit[u].target)
            fs_env(b, &k->unit[u], u);
    if (has_secondary(k))
        put(b, "    col.rgb = clamp(col.rgb + sec.rgb, 0.0, 1.0);\n");
    if (k->fog)
        fs_fog(b, k);
    put(b, "    gl_FragColor = col;\n");
    if (patch(k))
        put(b, "    gl_FragDepth = patch_depth;\n");
    else if (k->flags & QGL__KF_DEPTH)
        put(b, "    vec4 scr = f_w * lam;\n    gl_FragDepth = dot(scr, f_z) / dot(scr, vec4(1.0));\n");
    put(b, "}\n");
}

/* ---- compiling and caching ------------------------------------------------------------------- */

static void warn(const qgl__key *k, uint32_t hash, const char *what, const char *log)
{
    fprintf(stderr, "quadgl: warning: shader path program (key %08x) %s; its quads take the CPU fallback\n", hash,
            what);
    if (getenv("QUADGL_DEBUG"))
        fprintf(stderr, "%s\n(key: %zu bytes, %d varying slots)\n", log, sizeof *k, qgl__key_slots(k));
}

GLuint qgl__shader_compile(struct qgl__gl *gl, GLenum type, int count, const char *const *src, char *log, int size)
{
    GLuint sh = gl->CreateShader(type);
    gl->ShaderSource(sh, count, src, NULL);
    gl->CompileShader(sh);
    GLint ok = 0;
    gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok)
        return sh;
    gl->GetShaderInfoLog(sh, size, NULL, log);
    gl->DeleteShader(sh);
    return 0;
}

int qgl__program_link(struct qgl__gl *gl, GLuint prog, char *log, int size)
{
    gl->LinkProgram(prog);
    GLint ok = 0;
    gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok)
        gl->GetProgramInfoLog(prog, size, NULL, log);
    return ok;
}

static GLuint compile(qgl_context *ctx, GLenum type, const char *src, const qgl__key *k, uint32_t hash)
{
    char log[4096];
    GLuint sh = qgl__shader_compile(&ctx->gl, type, 1, &src, log, sizeof log);
    if (!sh) {
        if (getenv("QUADGL_DEBUG"))
            fprintf(stderr, "%s\n", src);
        warn(k, hash, "did not compile", log);
    }
    return sh;
}

static int link(qgl_context *ctx, GLuint prog, const qgl__key *k, uint32_t hash)
{
    struct qgl__gl *gl = &ctx->gl;
    if (lit(k) && (k->flags & QGL__KF_MATERIAL) && gl->BindAttribLocation)
        for (int i = 0; i < QGL__NMATERIAL; i++)
            gl->BindAttribLocation(prog, QGL__LOC_MATERIAL + (GLuint)i, material_names[i]);
    char log[4096];
    int ok = qgl__program_link(gl, prog, log, sizeof log);
    if (!ok)
        warn(k, hash, "did not link", log);
    return ok;
}

/* Each sampler reads its own unit. */
static void bind_samplers(qgl_context *ctx, GLuint prog, const qgl__key *k)
{
    struct qgl__gl *gl = &ctx->gl;
    GLint cur = 0;
    gl->GetIntegerv(GL_CURRENT_PROGRAM, &cur);
    gl->UseProgram(prog);
    for (int u = 0; u < k->nunits; u++)
        if (k->unit[u].target) {
            char name[16];
            snprintf(name, sizeof name, "u_tex%d", u);
            gl->Uniform1i(gl->GetUniformLocation(prog, name), u);
        }
    gl->UseProgram((GLuint)cur);
}

static GLuint build(qgl_context *ctx, const qgl__key *k, uint32_t hash)
{
    struct qgl__gl *gl = &ctx->gl;
    sb src[3] = {{0}};
    vs_source(&src[0], k);
    gs_source(&src[1], k);
    fs_source(&src[2], k);
    static const GLenum types[3] = {GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER};
    GLuint sh[3] = {0}, prog = 0;
    int ok = !src[0].oom && !src[1].oom && !src[2].oom;
    for (int i = 0; i < 3 && ok; i++)
        ok = (sh[i] = compile(ctx, types[i], src[i].p, k, hash)) != 0;
    if (ok) {
        prog = gl->CreateProgram();
        for (int i = 0; i < 3; i++)
            gl->AttachShader(prog, sh[i]);
        if (!link(ctx, prog, k, hash)) {
            gl->DeleteProgram(prog);
            prog = 0;
        }
    }
    for (int i = 0; i < 3; i++) {
        if (sh[i])
            gl->DeleteShader(sh[i]);
        free(src[i].p);
    }
    if (prog)
        bind_samplers(ctx, prog, k);
    return prog;
}

/* FNV-1a over the key's bytes (the key has no padding holes: every byte is set). */
static uint32_t hash_key(const qgl__key *k)
{
    const unsigned char *p = (const unsigned char *)k;
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < sizeof *k; i++)
        h = (h ^ p[i]) * 16777619u;
    return h;
}

GLuint qgl__program(qgl_context *ctx, const qgl__key *key)
{
    qgl__key plain;
    if (!key) {
        memset(&plain, 0, sizeof plain);
        key = &plain;
    }
    uint32_t h = hash_key(key);
    for (int i = 0; i < ctx->nprograms; i++)
        if (ctx->programs[i].hash == h && !memcmp(&ctx->programs[i].key, key, sizeof *key))
            return ctx->programs[i].prog;
    GLuint prog = build(ctx, key, h);
    int slot;
    if (ctx->nprograms < QGL__MAX_PROGRAMS) {
        slot = ctx->nprograms++;
    } else { /* full: evict in rotation */
        slot = ctx->next_evict;
        ctx->next_evict = (ctx->next_evict + 1) % QGL__MAX_PROGRAMS;
        if (ctx->programs[slot].prog)
            ctx->gl.DeleteProgram(ctx->programs[slot].prog);
    }
    ctx->programs[slot].hash = h;
    ctx->programs[slot].key = *key;
    ctx->programs[slot].prog = prog;
    ctx->programs[slot].failed = !prog;
    ctx->programs[slot].px_loc = prog ? ctx->gl.GetUniformLocation(prog, "u_px") : -1;
    ctx->programs[slot].px[0] = ctx->programs[slot].px[1] = 0;
    return prog;
}

void qgl__program_viewport(qgl_context *ctx, GLuint prog, const GLint viewport[4])
{
    float hw = 0.5f * (float)viewport[2], hh = 0.5f * (float)viewport[3];
    for (int i = 0; i < ctx->nprograms; i++)
        if (ctx->programs[i].prog == prog) {
            if (ctx->programs[i].px[0] != hw || ctx->programs[i].px[1] != hh) {
                ctx->gl.Uniform2f(ctx->programs[i].px_loc, hw, hh);
                ctx->programs[i].px[0] = hw;
                ctx->programs[i].px[1] = hh;
            }
            return;
        }
}

void qgl__programs_free(qgl_context *ctx)
{
    for (int i = 0; i < ctx->nprograms; i++)
        if (ctx->programs[i].prog && !ctx->gl_gone)
            ctx->gl.DeleteProgram(ctx->programs[i].prog);
    ctx->nprograms = 0;
    ctx->next_evict = 0;
}
