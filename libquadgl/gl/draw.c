/* draw.c: draw a batch of captured quads: read the GL state, plan each quad, run the paths.
 *
 * The state is read once per batch (matrices, viewport, shade model, what is enabled) and
 * decides whether the shader path can reproduce it ("modelled"). Each quad is then planned:
 * polygon mode line/point and select/feedback render modes go to the driver as quads; in
 * AUTO a quad the diagonal split renders exactly (planar, attributes affine in object space)
 * or invisibly (bounding box under invisible_area_px) is split by the driver; the rest takes
 * the shader path when the state is modelled and the CPU subdivision otherwise. Quads are
 * drawn in their original order, as runs of consecutive quads sharing a path (blending and
 * equal depths make order visible). All vertices are uploaded once into our own buffer,
 * behind our own vertex array object; afterwards the program, the bindings, the client
 * active texture and the current values of every attribute we streamed are restored. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

size_t qgl__nquads(qgl_topology topo, size_t n)
{
    if (topo == QGL_QUADS)
        return n / 4;
    return n >= 4 ? (n - 2) / 2 : 0;
}

size_t qgl__corner(qgl_topology topo, size_t q, int c)
{
    static const int strip[4] = {0, 1, 3, 2};
    return topo == QGL_QUADS ? 4 * q + (size_t)c : 2 * q + (size_t)strip[c];
}

/* ---- state --------------------------------------------------------------------------------- */

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

/* Texture targets and the GL version that has them (querying an unknown one is an error the
 * application would see). */
static const struct { GLenum target; int version; } tex_targets[] = {
    {GL_TEXTURE_1D, 10}, {GL_TEXTURE_2D, 10}, {GL_TEXTURE_3D, 12}, {GL_TEXTURE_CUBE_MAP, 13},
    {GL_TEXTURE_RECTANGLE, 31}};
#define NTARGETS (sizeof tex_targets / sizeof tex_targets[0])

/* Texture unit 0 as the shader path sees it; returns 0 when it cannot reproduce it. */
static int query_unit0(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    int ok = 1;
    for (size_t t = 0; t < NTARGETS; t++)
        if (tex_targets[t].target != GL_TEXTURE_2D && ctx->version >= tex_targets[t].version &&
            gl->IsEnabled(tex_targets[t].target))
            ok = 0;
    st->texture2d = gl->IsEnabled(GL_TEXTURE_2D);
    gl->GetDoublev(GL_TEXTURE_MATRIX, st->texmat);
    static const GLenum gens[] = {GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R, GL_TEXTURE_GEN_Q};
    for (int i = 0; i < 4; i++)
        if (gl->IsEnabled(gens[i]))
            ok = 0, st->lit_or_fog = 1;
    if (!st->texture2d)
        return ok;
    GLint env = GL_MODULATE, alpha = 0, red = 0, lum = 0, inten = 0;
    gl->GetTexEnviv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, &env);
    gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_ALPHA_SIZE, &alpha);
    gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_RED_SIZE, &red);
    gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_LUMINANCE_SIZE, &lum);
    gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTENSITY_SIZE, &inten);
    st->tex_replace = env == GL_REPLACE;
    st->tex_no_alpha = alpha == 0;
    if (env != GL_MODULATE && env != GL_REPLACE)
        ok = 0;
    if (alpha > 0 && red == 0 && lum == 0 && inten == 0) /* GL_ALPHA: colour passes through */
        ok = 0;
    return ok;
}

static int other_units_enabled(qgl_context *ctx)
{
    struct qgl__gl *gl = &ctx->gl;
    int any = 0;
    for (GLint u = 1; u < ctx->max_units && !any; u++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t t = 0; t < NTARGETS; t++)
            any |= ctx->version >= tex_targets[t].version && gl->IsEnabled(tex_targets[t].target);
    }
    return any;
}

static int fixed_function_extras(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    int extra = 0;
    if (gl->IsEnabled(GL_LIGHTING) || gl->IsEnabled(GL_FOG) || (ctx->version >= 14 && gl->IsEnabled(GL_COLOR_SUM)))
        extra = 1, st->lit_or_fog = 1;
    for (GLint i = 0; i < ctx->max_clip_planes; i++)
        extra |= gl->IsEnabled(GL_CLIP_PLANE0 + (GLenum)i);
    if (ctx->has_arb_programs)
        extra |= gl->IsEnabled(GL_VERTEX_PROGRAM_ARB) || gl->IsEnabled(GL_FRAGMENT_PROGRAM_ARB);
    return extra;
}

void qgl__query_state(qgl_context *ctx, qgl__state *st)
{
    struct qgl__gl *gl = &ctx->gl;
    double mv[16], pr[16];
    memset(st, 0, sizeof *st);
    gl->GetIntegerv(GL_RENDER_MODE, &st->render_mode);
    gl->GetIntegerv(GL_POLYGON_MODE, st->polygon_mode);
    if (ctx->version >= 20)
        gl->GetIntegerv(GL_CURRENT_PROGRAM, &st->program);
    gl->GetIntegerv(GL_SHADE_MODEL, &st->shade_model);
    gl->GetIntegerv(GL_VIEWPORT, st->viewport);
    gl->GetIntegerv(GL_ACTIVE_TEXTURE, &st->active_texture);
    gl->GetDoublev(GL_MODELVIEW_MATRIX, mv);
    gl->GetDoublev(GL_PROJECTION_MATRIX, pr);
    mat_mul(pr, mv, st->mvp);
    st->polygon_offset = gl->IsEnabled(GL_POLYGON_OFFSET_FILL);
    int extra = fixed_function_extras(ctx, st);
    if (st->active_texture != GL_TEXTURE0)
        gl->ActiveTexture(GL_TEXTURE0);
    int unit0 = query_unit0(ctx, st);
    int others = other_units_enabled(ctx);
    if (st->active_texture != GL_TEXTURE0 || ctx->max_units > 1)
        gl->ActiveTexture((GLenum)st->active_texture);
    GLboolean clamp = GL_TRUE;
    if (ctx->shader_level)
        gl->GetBooleanv(GL_CLAMP_VERTEX_COLOR, &clamp);
    st->modelled = ctx->shader_level && !extra && unit0 && !others && st->program == 0 && clamp;
    if (st->program)
        st->lit_or_fog = 1; /* an application program: per-vertex work unknown */
}

/* ---- planning --------------------------------------------------------------------------------- */

static void transform(const double m[16], const float p[4], double out[4])
{
    for (int r = 0; r < 4; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] * p[3];
}

static int ensure(void **p, size_t *cap, size_t n, size_t elem)
{
    if (n <= *cap)
        return 1;
    size_t c = n > 2 * *cap ? n : 2 * *cap;
    void *q = realloc(*p, c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

/* Bounding box of the projected quad, in pixels squared. */
static double bbox_area_px(const double *clip[4], const GLint vp[4])
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int i = 0; i < 4; i++) {
        double x = clip[i][0] / clip[i][3], y = clip[i][1] / clip[i][3];
        x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
    }
    return (x1 - x0) * 0.5 * vp[2] * (y1 - y0) * 0.5 * vp[3];
}

/* The attributes that reach the picture, per corner, for the affinity test: colour when
 * smooth, texture coordinates of unit 0 after the texture matrix when texturing, and with a
 * state the shader path does not model every captured attribute. */
static int gather_attribs(const qgl__state *st, const qgl__verts *v, const size_t idx[4], double *attr)
{
    int n = 0;
    for (int c = 0; c < 4; c++) {
        double *a = attr + c * 16;
        int k = 0;
        size_t i = idx[c];
        if ((v->mask & QGL__A_COLOR) && st->shade_model != GL_FLAT)
            for (int j = 0; j < 4; j++)
                a[k++] = v->col[4 * i + j];
        if ((v->mask & QGL__A_TEX0) && (st->texture2d || !st->modelled)) {
            double t[4];
            transform(st->texmat, v->tex[0] + 4 * i, t);
            for (int j = 0; j < 4; j++)
                a[k++] = t[j];
        }
        if (!st->modelled) {
            if (v->mask & QGL__A_COLOR2)
                for (int j = 0; j < 3; j++)
                    a[k++] = v->col2[3 * i + j];
            if (v->mask & QGL__A_FOG)
                a[k++] = v->fog[i];
            for (int u = 1; u < QGL_MAX_TEXUNITS; u++)
                if (v->mask & (QGL__A_TEX0 << u))
                    for (int j = 0; j < 4; j++)
                        a[k++] = v->tex[u][4 * i + j];
        }
        n = k;
    }
    return n;
}

/* Re-pack corner-major attributes (16 slots each) into the n-per-corner layout of the core. */
static int split_is_exact(const qgl__state *st, const qgl__verts *v, const size_t idx[4], int *planar)
{
    double p[4][3], attr[64], packed[64];
    for (int c = 0; c < 4; c++) {
        const float *q = v->pos + 4 * idx[c];
        if (!(q[3] > 0))
            return *planar = 0;
        for (int k = 0; k < 3; k++)
            p[c][k] = q[k] / q[3];
    }
    *planar = qgl_is_planar(p, 1e-6);
    if (!*planar || st->lit_or_fog)
        return 0;
    int n = gather_attribs(st, v, idx, attr);
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < n; k++)
            packed[c * n + k] = attr[c * 16 + k];
    return qgl_split_is_exact(p, packed, n, 1e-5);
}

static unsigned char plan_quad(qgl_context *ctx, const qgl__state *st, const qgl__verts *v,
                               qgl_topology topo, size_t q)
{
    size_t idx[4];
    const double *clip[4];
    int external = 0, behind = 0;
    for (int c = 0; c < 4; c++) {
        idx[c] = qgl__corner(topo, q, c);
        clip[c] = ctx->clip + 4 * idx[c];
        external |= !(clip[c][3] > 0);
        behind += !(clip[c][3] > 0);
    }
    if (behind == 4)
        return QGL__P_SPLIT; /* entirely behind the eye: the clipper removes it */
    if (ctx->method == QGL_METHOD_SPLIT)
        return QGL__P_SPLIT;
    if (ctx->method == QGL_METHOD_SUBDIV)
        return QGL__P_SUBDIV;
    if (ctx->method == QGL_METHOD_AUTO && !external && bbox_area_px(clip, st->viewport) < ctx->invisible_area_px)
        return QGL__P_SPLIT;
    int planar = 0;
    int exact = split_is_exact(st, v, idx, &planar);
    if (ctx->method == QGL_METHOD_AUTO && exact)
        return QGL__P_SPLIT;
    if (!st->modelled || (!planar && st->polygon_offset))
        return QGL__P_SUBDIV;
    /* With a corner behind the eye the cover is the clipped split; its rasterized depth is the
     * one consistent with that clipping, so eq. 4 depth is used for visible quads only. */
    if (external)
        return QGL__P_MVC | QGL__P_EXTERNAL;
    return QGL__P_MVC | (planar ? 0 : QGL__P_DEPTH);
}

/* ---- drawing through the driver ---------------------------------------------------------------- */

typedef struct saved {
    GLint program, vao, vbo, client_tex;
    unsigned restore_current; /* attributes whose current value we must put back */
    float col[4], nrm[4], col2[4], fog[4], tex[QGL_MAX_TEXUNITS][4];
    GLboolean edge;
} saved;

static void save(qgl_context *ctx, const qgl__state *st, unsigned mask, saved *s)
{
    struct qgl__gl *gl = &ctx->gl;
    s->program = st->program;
    s->restore_current = mask;
    gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    gl->GetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->vbo);
    gl->GetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &s->client_tex);
    if (mask & QGL__A_COLOR)
        gl->GetFloatv(GL_CURRENT_COLOR, s->col);
    if (mask & QGL__A_NORMAL)
        gl->GetFloatv(GL_CURRENT_NORMAL, s->nrm);
    if (mask & QGL__A_COLOR2)
        gl->GetFloatv(GL_CURRENT_SECONDARY_COLOR, s->col2);
    if (mask & QGL__A_FOG)
        gl->GetFloatv(GL_CURRENT_FOG_COORD, s->fog);
    if (mask & QGL__A_EDGE)
        gl->GetBooleanv(GL_EDGE_FLAG, &s->edge);
    if (mask & (QGL__A_TEX0 * 15u)) {
        for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
            if (mask & (QGL__A_TEX0 << u)) {
                gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
                gl->GetFloatv(GL_CURRENT_TEXTURE_COORDS, s->tex[u]);
            }
        gl->ActiveTexture((GLenum)st->active_texture);
    }
}

static void restore(qgl_context *ctx, const saved *s)
{
    struct qgl__gl *gl = &ctx->gl;
    unsigned m = s->restore_current;
    gl->UseProgram((GLuint)s->program);
    gl->BindVertexArray((GLuint)s->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, (GLuint)s->vbo);
    gl->ClientActiveTexture((GLenum)s->client_tex);
    if (m & QGL__A_COLOR)
        gl->Color4fv(s->col);
    if (m & QGL__A_NORMAL)
        gl->Normal3fv(s->nrm);
    if (m & QGL__A_COLOR2)
        gl->SecondaryColor3fv(s->col2);
    if (m & QGL__A_FOG)
        gl->FogCoordf(s->fog[0]);
    if (m & QGL__A_EDGE)
        gl->EdgeFlag(s->edge);
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (m & (QGL__A_TEX0 << u))
            gl->MultiTexCoord4fv(GL_TEXTURE0 + (GLenum)u, s->tex[u]);
}

/* Upload v into our buffer (one block per attribute) and point our VAO's arrays at it. */
static void upload(qgl_context *ctx, const qgl__verts *v)
{
    struct qgl__gl *gl = &ctx->gl;
    size_t n = v->n, off = 0;
    struct { unsigned bit; const void *data; size_t size; } blocks[6 + QGL_MAX_TEXUNITS] = {
        {0, v->pos, 16}, {QGL__A_COLOR, v->col, 16}, {QGL__A_NORMAL, v->nrm, 12},
        {QGL__A_COLOR2, v->col2, 12}, {QGL__A_FOG, v->fog, 4}, {QGL__A_EDGE, v->edge, 1}};
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++) {
        blocks[6 + u].bit = QGL__A_TEX0 << u;
        blocks[6 + u].data = v->tex[u];
        blocks[6 + u].size = 16;
    }
    size_t total = 0;
    for (size_t b = 0; b < sizeof blocks / sizeof blocks[0]; b++)
        if (!blocks[b].bit || (v->mask & blocks[b].bit))
            total += (n * blocks[b].size + 15) & ~(size_t)15;
    gl->BindVertexArray(ctx->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, ctx->vbo);
    if (total > ctx->vbo_size) { /* grow only: reallocating every batch costs page faults */
        ctx->vbo_size = total + total / 2;
        gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)ctx->vbo_size, NULL, GL_STREAM_DRAW);
    }
    for (size_t b = 0; b < sizeof blocks / sizeof blocks[0]; b++) {
        unsigned bit = blocks[b].bit;
        int on = !bit || (v->mask & bit);
        const void *at = (const void *)(uintptr_t)off;
        if (on)
            gl->BufferSubData(GL_ARRAY_BUFFER, (GLintptr)off, (GLsizeiptr)(n * blocks[b].size), blocks[b].data);
        GLenum array = 0;
        switch (bit) {
        case 0: gl->VertexPointer(4, GL_FLOAT, 0, at); array = GL_VERTEX_ARRAY; break;
        case QGL__A_COLOR: gl->ColorPointer(4, GL_FLOAT, 0, at); array = GL_COLOR_ARRAY; break;
        case QGL__A_NORMAL: gl->NormalPointer(GL_FLOAT, 0, at); array = GL_NORMAL_ARRAY; break;
        case QGL__A_COLOR2: gl->SecondaryColorPointer(3, GL_FLOAT, 0, at); array = GL_SECONDARY_COLOR_ARRAY; break;
        case QGL__A_FOG: gl->FogCoordPointer(GL_FLOAT, 0, at); array = GL_FOG_COORD_ARRAY; break;
        case QGL__A_EDGE: gl->EdgeFlagPointer(0, at); array = GL_EDGE_FLAG_ARRAY; break;
        default:
            gl->ClientActiveTexture(GL_TEXTURE0 + (GLenum)(b - 6));
            gl->TexCoordPointer(4, GL_FLOAT, 0, at);
            array = GL_TEXTURE_COORD_ARRAY;
        }
        if (on)
            gl->EnableClientState(array);
        else
            gl->DisableClientState(array);
        if (on)
            off += (n * blocks[b].size + 15) & ~(size_t)15;
    }
}

/* Corner indices (lines_adjacency order) of strip quads, in our element buffer. */
static int upload_strip_indices(qgl_context *ctx, size_t nq)
{
    if (!ensure((void **)&ctx->idx, &ctx->idx_cap, 4 * nq, sizeof(uint32_t)))
        return 0;
    for (size_t q = 0; q < nq; q++)
        for (int c = 0; c < 4; c++)
            ctx->idx[4 * q + c] = (uint32_t)qgl__corner(QGL_QUAD_STRIP, q, c);
    ctx->gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(16 * nq), ctx->idx, GL_STREAM_DRAW);
    return 1;
}

static void draw_split(qgl_context *ctx, qgl_topology topo, size_t q0, size_t nq, GLint app_program,
                       GLint *bound)
{
    if (*bound != app_program)
        ctx->gl.UseProgram((GLuint)(*bound = app_program));
    if (topo == QGL_QUADS)
        ctx->gl.DrawArrays(GL_QUADS, (GLint)(4 * q0), (GLsizei)(4 * nq));
    else
        ctx->gl.DrawArrays(GL_QUAD_STRIP, (GLint)(2 * q0), (GLsizei)(2 * nq + 2));
    ctx->stats.draws++;
}

/* The corner of a captured quad whose colour flat shading uses: the last vertex of the quad
 * (GL_QUADS 4k+3, corner 3; strip 2k+3, corner 2) unless quads follow a first-vertex
 * provoking convention. */
int qgl__flat_corner(qgl_context *ctx, qgl_topology topo)
{
    if (ctx->quads_follow_pv) {
        GLint pv = GL_LAST_VERTEX_CONVENTION;
        ctx->gl.GetIntegerv(GL_PROVOKING_VERTEX, &pv);
        if (pv == GL_FIRST_VERTEX_CONVENTION)
            return 0;
    }
    return topo == QGL_QUADS ? 3 : 2;
}

static unsigned program_key(qgl_context *ctx, const qgl__state *st, qgl_topology topo, unsigned char path)
{
    unsigned key = QGL__K_COLOR;
    int corner = qgl__flat_corner(ctx, topo);
    if (st->shade_model == GL_FLAT)
        key |= QGL__K_FLAT | (unsigned)corner << QGL__K_CORNER_SHIFT;
    if (st->texture2d)
        key |= QGL__K_TEX | (st->tex_replace ? QGL__K_REPLACE : 0) | (st->tex_no_alpha ? QGL__K_NOALPHA : 0);
    if (path & QGL__P_DEPTH)
        key |= QGL__K_DEPTH;
    if (path & QGL__P_EXTERNAL)
        key |= QGL__K_DISCARD;
    return key;
}

static int draw_mvc(qgl_context *ctx, const qgl__state *st, qgl_topology topo, size_t q0, size_t nq,
                    unsigned char path, GLint *bound)
{
    GLuint prog = qgl__program(ctx, program_key(ctx, st, topo, path));
    if (!prog)
        return 0;
    if (*bound != (GLint)prog)
        ctx->gl.UseProgram(prog), *bound = (GLint)prog;
    if (topo == QGL_QUADS)
        ctx->gl.DrawArrays(GL_LINES_ADJACENCY, (GLint)(4 * q0), (GLsizei)(4 * nq));
    else
        ctx->gl.DrawElements(GL_LINES_ADJACENCY, (GLsizei)(4 * nq), GL_UNSIGNED_INT,
                             (const void *)(uintptr_t)(16 * q0));
    ctx->stats.draws++;
    return 1;
}

static void draw_subdiv(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo,
                        size_t q0, size_t nq, GLint app_program, GLint *bound)
{
    ctx->sub.n = 0;
    ctx->sub.mask = v->mask & ~(unsigned)QGL__A_EDGE;
    for (size_t q = q0; q < q0 + nq; q++)
        qgl__subdivide(ctx, st, v, topo, q, &ctx->sub);
    if (!ctx->sub.n)
        return;
    if (*bound != app_program)
        ctx->gl.UseProgram((GLuint)(*bound = app_program));
    upload(ctx, &ctx->sub);
    ctx->gl.DrawArrays(GL_TRIANGLES, 0, (GLsizei)ctx->sub.n);
    ctx->stats.draws++;
    ctx->stats.subdiv_triangles += ctx->sub.n / 3;
    upload(ctx, v); /* later runs draw from the batch again */
}

static void count(qgl_context *ctx, unsigned char path, size_t nq)
{
    switch (path & 15) {
    case QGL__P_SPLIT: ctx->stats.split += nq; break;
    case QGL__P_MVC: ctx->stats.mvc += nq; break;
    case QGL__P_SUBDIV: ctx->stats.subdiv += nq; break;
    default: ctx->stats.passthrough += nq;
    }
}

/* ---- immediate replay (contexts without vertex array objects) ------------------------------- */

static void replay_vertex(struct qgl__gl *gl, const qgl__verts *v, size_t i)
{
    unsigned m = v->mask;
    if (m & QGL__A_COLOR)
        gl->Color4fv(v->col + 4 * i);
    if (m & QGL__A_NORMAL)
        gl->Normal3fv(v->nrm + 3 * i);
    if (m & QGL__A_COLOR2)
        gl->SecondaryColor3fv(v->col2 + 3 * i);
    if (m & QGL__A_FOG)
        gl->FogCoordf(v->fog[i]);
    if (m & QGL__A_EDGE)
        gl->EdgeFlag(v->edge[i]);
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (m & (QGL__A_TEX0 << u))
            gl->MultiTexCoord4fv(GL_TEXTURE0 + (GLenum)u, v->tex[u] + 4 * i);
    gl->Vertex4fv(v->pos + 4 * i);
}

static void replay(qgl_context *ctx, GLenum mode, const qgl__verts *v, size_t first, size_t n)
{
    ctx->gl.Begin(mode);
    for (size_t i = first; i < first + n; i++)
        replay_vertex(&ctx->gl, v, i);
    ctx->gl.End();
    ctx->stats.draws++;
}

/* Without VAOs we cannot stream arrays without touching the application's client state, so
 * the driver gets the vertices as immediate calls (split, pass-through, subdivision). */
static void draw_replay(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo,
                        size_t q0, size_t nq, unsigned char path)
{
    if ((path & 15) == QGL__P_SUBDIV) {
        ctx->sub.n = 0;
        ctx->sub.mask = v->mask & ~(unsigned)QGL__A_EDGE;
        for (size_t q = q0; q < q0 + nq; q++)
            qgl__subdivide(ctx, st, v, topo, q, &ctx->sub);
        ctx->stats.subdiv_triangles += ctx->sub.n / 3;
        replay(ctx, GL_TRIANGLES, &ctx->sub, 0, ctx->sub.n);
    } else if (topo == QGL_QUADS) {
        replay(ctx, GL_QUADS, v, 4 * q0, 4 * nq);
    } else {
        replay(ctx, GL_QUAD_STRIP, v, 2 * q0, 2 * nq + 2);
    }
}

/* ---- the batch -------------------------------------------------------------------------------- */

static int plan(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t nq)
{
    if (!ensure((void **)&ctx->path, &ctx->path_cap, nq, 1))
        return 0;
    int pass = st->render_mode != GL_RENDER || st->polygon_mode[0] != GL_FILL || st->polygon_mode[1] != GL_FILL;
    if (pass) {
        memset(ctx->path, QGL__P_PASS, nq);
        return 1;
    }
    if (!ensure((void **)&ctx->clip, &ctx->clip_cap, 4 * v->n, sizeof(double)))
        return 0;
    for (size_t i = 0; i < v->n; i++)
        transform(st->mvp, v->pos + 4 * i, ctx->clip + 4 * i);
    for (size_t q = 0; q < nq; q++) {
        unsigned char p = plan_quad(ctx, st, v, topo, q);
        if ((p & 15) == QGL__P_MVC && !ctx->has_vao)
            p = QGL__P_SUBDIV;
        ctx->path[q] = p;
    }
    return 1;
}

int qgl__draw(qgl_context *ctx, const qgl__verts *v, qgl_topology topo)
{
    size_t nq = qgl__nquads(topo, v->n);
    if (!nq)
        return 0;
    qgl__state st;
    qgl__query_state(ctx, &st);
    if (!plan(ctx, &st, v, topo, nq))
        return -1;
    ctx->stats.quads += nq;
    saved sv;
    if (ctx->has_vao) {
        save(ctx, &st, v->mask, &sv);
        upload(ctx, v);
        if (topo == QGL_QUAD_STRIP && !upload_strip_indices(ctx, nq))
            return -1;
    }
    GLint bound = st.program;
    for (size_t q0 = 0; q0 < nq;) {
        size_t q1 = q0 + 1;
        while (q1 < nq && ctx->path[q1] == ctx->path[q0])
            q1++;
        unsigned char p = ctx->path[q0];
        count(ctx, p, q1 - q0);
        if (!ctx->has_vao)
            draw_replay(ctx, &st, v, topo, q0, q1 - q0, p);
        else if ((p & 15) == QGL__P_MVC) {
            if (!draw_mvc(ctx, &st, topo, q0, q1 - q0, p, &bound))
                draw_subdiv(ctx, &st, v, topo, q0, q1 - q0, st.program, &bound);
        } else if ((p & 15) == QGL__P_SUBDIV)
            draw_subdiv(ctx, &st, v, topo, q0, q1 - q0, st.program, &bound);
        else
            draw_split(ctx, topo, q0, q1 - q0, st.program, &bound);
        q0 = q1;
    }
    if (ctx->has_vao)
        restore(ctx, &sv);
    return (int)nq;
}
