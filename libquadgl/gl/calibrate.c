/* calibrate.c: what the shader path, the split and the mean value grid cost on this driver,
 * measured once per renderer in the process, and the planner's cost model.
 *
 * Which is cheapest depends on the driver (on a GPU the shader path is nearly free; on
 * llvmpipe every fragment-shader instruction and every triangle is CPU time), so it is
 * measured rather than assumed: off screen, in a 128 x 128 framebuffer object of our own,
 * with every piece of application state we touch saved and put back, and everything that
 * could change a draw's cost switched off. Five timed
 * draws (each finished with glFinish, the best of two): an empty one (the fixed cost of a
 * draw and a finish, taken off the others), two window-sized quads and 256 quads of
 * 4 x 4 pixels through the shader path and through the split, which give per quad and per
 * pixel costs, and 16 quads of 32 x 32 pixels as the 8 x 8 grid (our vertex weights, upload
 * and the driver's triangles), which gives a cost per grid triangle. The model per quad of
 * area A: shader path mvc_quad + mvc_px A; grid of T triangles grid_tri T + split_px A.
 * The measurement must fit in 20 ms; one over that, a failed draw or framebuffer, or a figure
 * that is not positive leaves the costs invalid and the planner keeps the shader path. Not
 * counted: one untimed draw of each kind first, in which drivers compile lazily (llvmpipe
 * compiles each program's code for the state at its first draw: about 40 ms for the fixed
 * function and 250 ms for the shader path's program here, which the application's first
 * draws pay for its own state as well); its time is kept as warm_ms. QUADGL_COSTS=mq,mf,sf,gt
 * (nanoseconds) replaces the measurement (validated the same way). */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gl_internal.h"

#define SIZE 128
#define BUDGET_MS 20.0

static struct {
    char renderer[192];
    struct qgl__costs costs;
} cache[8];
static int ncache;
static pthread_mutex_t cache_lock = PTHREAD_MUTEX_INITIALIZER;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* Every figure positive and finite. */
static int sane(struct qgl__costs *c)
{
    const double v[4] = {c->mvc_quad, c->mvc_px, c->split_px, c->grid_tri};
    c->valid = 1;
    for (int i = 0; i < 4; i++)
        c->valid &= v[i] > 0 && v[i] < 1e9;
    return c->valid;
}

/* ---- the scenes ----------------------------------------------------------------------------- */

static void put_quad(qgl__verts *v, float x0, float y0, float x1, float y1)
{
    static const float colour[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {0, 0, 0, 1}};
    const float x[4] = {x0, x1, x1, x0}, y[4] = {y0, y0, y1, y1};
    for (int c = 0; c < 4; c++) {
        size_t i = v->n++;
        float *p = v->pos + 4 * i;
        p[0] = x[c], p[1] = y[c], p[2] = 0, p[3] = 1;
        memcpy(v->col + 4 * i, colour[c], sizeof colour[c]);
    }
}

/* n x n quads tiling the window, each `fill` of its cell (in NDC; the matrices are identity). */
static int tiles(qgl__verts *v, int n, float fill)
{
    v->n = 0;
    v->mask = QGL__A_COLOR;
    if (!qgl__verts_reserve(v, 4 * (size_t)n * (size_t)n, QGL__A_COLOR))
        return 0;
    float cell = 2.0f / (float)n;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            float x = -1 + cell * (float)i, y = -1 + cell * (float)j;
            put_quad(v, x, y, x + cell * fill, y + cell * fill);
        }
    return 1;
}

/* ---- the measurement ------------------------------------------------------------------------- */

/* Caps that change what a draw costs; off for the measurement. */
static const GLenum caps_off[] = {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_BLEND, GL_ALPHA_TEST, GL_SCISSOR_TEST,
                                  GL_CULL_FACE, GL_LIGHTING, GL_FOG, GL_COLOR_LOGIC_OP, GL_POLYGON_OFFSET_FILL,
                                  GL_POLYGON_STIPPLE, GL_POLYGON_SMOOTH, GL_COLOR_SUM, GL_PRIMITIVE_RESTART,
                                  GL_RASTERIZER_DISCARD};
static const GLenum textures_off[] = {GL_TEXTURE_1D, GL_TEXTURE_2D, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP,
                                      GL_TEXTURE_RECTANGLE};
#define NCAPS (sizeof caps_off / sizeof caps_off[0])
#define NTEXTURES (sizeof textures_off / sizeof textures_off[0])
#define MAX_OFF 128

/* The application's state that the measurement changes, saved by hand: glPushAttrib would make
 * the driver allocate its whole attribute record, which Mesa keeps for the rest of the process
 * (2.6 MB allocated in peepers), and it fails, as
 * glPushMatrix does, where the application's stack is full. Blending and the scissor test are
 * switched at draw buffer and viewport 0 alone where GL has them per index, so that the others
 * keep theirs. */
typedef struct saved {
    GLint draw_fb, read_fb, rb, program, vao, vbo, active, client, matrix_mode, shade, poly[2];
    GLfloat viewport[4], matrix[2][16];
    GLboolean mask[4];
    int per_buffer, vp_array; /* per draw buffer (GL 3.0), and per viewport (GL 4.1) state */
    struct {
        GLenum cap;
        GLint unit; /* the texture unit of a texture target, else -1 */
        int indexed;
    } off[MAX_OFF]; /* what was on and is now off */
    int noff;
} saved;
static const GLenum stacks[2] = {GL_PROJECTION, GL_MODELVIEW};

static int have_entry_points(const struct qgl__gl *gl)
{
    const void *need[] = {gl->Enable, gl->Disable, gl->Finish, gl->Viewport, gl->MatrixMode, gl->LoadIdentity,
                          gl->LoadMatrixf, gl->PolygonMode, gl->ShadeModel, gl->ColorMask, gl->GenFramebuffers,
                          gl->DeleteFramebuffers, gl->BindFramebuffer, gl->GenRenderbuffers,
                          gl->DeleteRenderbuffers, gl->BindRenderbuffer, gl->RenderbufferStorage,
                          gl->FramebufferRenderbuffer, gl->CheckFramebufferStatus};
    for (size_t i = 0; i < sizeof need / sizeof need[0]; i++)
        if (!need[i])
            return 0;
    return 1;
}

static void switch_off(const struct qgl__gl *gl, saved *s, GLenum cap, GLint unit)
{
    int indexed = cap == GL_BLEND ? s->per_buffer : cap == GL_SCISSOR_TEST && s->vp_array;
    if (s->noff == MAX_OFF || !(indexed ? gl->IsEnabledi(cap, 0) : gl->IsEnabled(cap)))
        return;
    if (indexed)
        gl->Disablei(cap, 0);
    else
        gl->Disable(cap);
    s->off[s->noff].cap = cap, s->off[s->noff].unit = unit, s->off[s->noff].indexed = indexed;
    s->noff++;
}

static void enter(qgl_context *ctx, saved *s)
{
    struct qgl__gl *gl = &ctx->gl;
    GLint vp[4];
    s->per_buffer = ctx->version >= 30 && gl->IsEnabledi && gl->Enablei && gl->Disablei && gl->ColorMaski &&
                    gl->GetBooleani_v;
    s->vp_array = s->per_buffer && (ctx->version >= 41 || qgl__has_extension(ctx, "GL_ARB_viewport_array")) &&
                  gl->ViewportIndexedf && gl->GetFloati_v;
    gl->GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fb);
    gl->GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fb);
    gl->GetIntegerv(GL_RENDERBUFFER_BINDING, &s->rb);
    gl->GetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    gl->GetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->vbo);
    gl->GetIntegerv(GL_ACTIVE_TEXTURE, &s->active);
    gl->GetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &s->client);
    gl->GetIntegerv(GL_MATRIX_MODE, &s->matrix_mode);
    gl->GetIntegerv(GL_SHADE_MODEL, &s->shade);
    gl->GetIntegerv(GL_POLYGON_MODE, s->poly);
    if (s->vp_array) {
        gl->GetFloati_v(GL_VIEWPORT, 0, s->viewport);
    } else {
        gl->GetIntegerv(GL_VIEWPORT, vp);
        for (int i = 0; i < 4; i++)
            s->viewport[i] = (GLfloat)vp[i];
    }
    if (s->per_buffer)
        gl->GetBooleani_v(GL_COLOR_WRITEMASK, 0, s->mask);
    else
        gl->GetBooleanv(GL_COLOR_WRITEMASK, s->mask);
    s->noff = 0;
    for (size_t i = 0; i < NCAPS; i++)
        switch_off(gl, s, caps_off[i], -1);
    for (GLint i = 0; i < ctx->max_clip_planes; i++)
        switch_off(gl, s, GL_CLIP_PLANE0 + (GLenum)i, -1);
    if (ctx->has_arb_vp)
        switch_off(gl, s, GL_VERTEX_PROGRAM_ARB, -1);
    if (ctx->has_arb_fp)
        switch_off(gl, s, GL_FRAGMENT_PROGRAM_ARB, -1);
    if (ctx->has_ati_fs)
        switch_off(gl, s, GL_FRAGMENT_SHADER_ATI, -1);
    for (GLint u = 0; u < ctx->max_units; u++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t t = 0; t < NTEXTURES; t++)
            switch_off(gl, s, textures_off[t], u);
    }
    gl->ActiveTexture(GL_TEXTURE0);
    for (int i = 0; i < 2; i++) {
        gl->MatrixMode(stacks[i]);
        gl->GetFloatv(stacks[i] == GL_PROJECTION ? GL_PROJECTION_MATRIX : GL_MODELVIEW_MATRIX, s->matrix[i]);
        gl->LoadIdentity();
    }
    gl->PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    gl->ShadeModel(GL_SMOOTH);
    if (s->per_buffer)
        gl->ColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    else
        gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (s->vp_array)
        gl->ViewportIndexedf(0, 0, 0, SIZE, SIZE);
    else
        gl->Viewport(0, 0, SIZE, SIZE);
}

static void leave(qgl_context *ctx, const saved *s)
{
    struct qgl__gl *gl = &ctx->gl;
    for (int i = 0; i < 2; i++) {
        gl->MatrixMode(stacks[i]);
        gl->LoadMatrixf(s->matrix[i]);
    }
    gl->MatrixMode((GLenum)s->matrix_mode);
    for (int i = 0; i < s->noff; i++) {
        if (s->off[i].unit >= 0)
            gl->ActiveTexture(GL_TEXTURE0 + (GLenum)s->off[i].unit);
        if (s->off[i].indexed)
            gl->Enablei(s->off[i].cap, 0);
        else
            gl->Enable(s->off[i].cap);
    }
    gl->ActiveTexture((GLenum)s->active);
    gl->ClientActiveTexture((GLenum)s->client);
    gl->PolygonMode(GL_FRONT, (GLenum)s->poly[0]);
    gl->PolygonMode(GL_BACK, (GLenum)s->poly[1]);
    gl->ShadeModel((GLenum)s->shade);
    if (s->per_buffer)
        gl->ColorMaski(0, s->mask[0], s->mask[1], s->mask[2], s->mask[3]);
    else
        gl->ColorMask(s->mask[0], s->mask[1], s->mask[2], s->mask[3]);
    if (s->vp_array)
        gl->ViewportIndexedf(0, s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    else
        gl->Viewport((GLint)s->viewport[0], (GLint)s->viewport[1], (GLsizei)s->viewport[2], (GLsizei)s->viewport[3]);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fb);
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, (GLuint)s->rb);
    gl->UseProgram((GLuint)s->program);
    gl->BindVertexArray((GLuint)s->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, (GLuint)s->vbo);
}

/* One way of drawing a scene, timed. */
typedef enum { DRAW_SPLIT, DRAW_MVC, DRAW_GRID } draw_kind;

typedef struct bench {
    qgl_context *ctx;
    qgl__state st;
    GLuint prog;
    int grid;        /* the 8 x 8 grid's number */
    double deadline; /* ms, not counting warm */
    double warm;     /* ms spent in the untimed first draws */
} bench;

static int draw(bench *b, const qgl__verts *v, draw_kind kind)
{
    struct qgl__gl *gl = &b->ctx->gl;
    if (kind == DRAW_GRID) {
        gl->UseProgram(0);
        return qgl__grid_draw_all(b->ctx, &b->st, v, b->grid);
    }
    gl->UseProgram(kind == DRAW_MVC ? b->prog : 0);
    if (kind == DRAW_MVC)
        qgl__program_viewport(b->ctx, b->prog, b->st.xf.viewport);
    return qgl__grid_draw_arrays(b->ctx, v, kind == DRAW_MVC ? GL_LINES_ADJACENCY : GL_QUADS);
}

/* Milliseconds of the best of two finished draws after an untimed one, in which the driver
 * compiles what it compiles lazily (its time goes to warm_ms, outside the budget); negative
 * when a draw failed or the budget ran out. */
static double timed(bench *b, const qgl__verts *v, draw_kind kind)
{
    struct qgl__gl *gl = &b->ctx->gl;
    double best = 1e30, w0 = now_ms();
    if (!draw(b, v, kind))
        return -1;
    gl->Finish();
    b->warm += now_ms() - w0;
    for (int r = 0; r < 2; r++) {
        double t0 = now_ms();
        if (!draw(b, v, kind))
            return -1;
        gl->Finish();
        double t = now_ms() - t0;
        best = t < best ? t : best;
    }
    return now_ms() - b->warm > b->deadline ? -1 : best;
}

/* The grid's clip positions are the scene's positions (identity matrices). */
static int clip_of(qgl_context *ctx, const qgl__verts *v)
{
    if (4 * v->n > ctx->clip_cap) {
        double *c = realloc(ctx->clip, 4 * v->n * sizeof *c);
        if (!c)
            return 0;
        ctx->clip = c;
        ctx->clip_cap = 4 * v->n;
    }
    for (size_t i = 0; i < 4 * v->n; i++)
        ctx->clip[i] = v->pos[i];
    return 1;
}

static int grid_number(int k)
{
    for (int g = 0; g < qgl_mvcgrid_count(); g++)
        if (qgl_mvcgrid_at(g) && qgl_mvcgrid_at(g)->k == k)
            return g;
    return -1;
}

/* The five timings, solved for the model's figures (see the file comment). */
static int measure(bench *b, qgl__verts *v, struct qgl__costs *c)
{
    double t_empty, t_mvc_big, t_mvc_tiny, t_split_big, t_split_tiny, t_grid;
    const double big_px = 2.0 * SIZE * SIZE, tiny_px = 256.0 * 16;
    if (!tiles(v, 1, 0.02f) || (t_empty = timed(b, v, DRAW_SPLIT)) < 0)
        return 0;
    if (!tiles(v, 1, 1) || !qgl__verts_reserve(v, 8, QGL__A_COLOR))
        return 0;
    for (int c4 = 0; c4 < 4; c4++) /* two window-sized quads */
        qgl__verts_copy(v, v->n++, v, (size_t)c4);
    if ((t_mvc_big = timed(b, v, DRAW_MVC)) < 0 || (t_split_big = timed(b, v, DRAW_SPLIT)) < 0)
        return 0;
    if (!tiles(v, 16, 0.5f) || (t_mvc_tiny = timed(b, v, DRAW_MVC)) < 0 ||
        (t_split_tiny = timed(b, v, DRAW_SPLIT)) < 0)
        return 0;
    if (!tiles(v, 4, 1) || !clip_of(b->ctx, v) || (t_grid = timed(b, v, DRAW_GRID)) < 0)
        return 0;
    /* per quad q and per pixel f from q n + f A = t - t_empty for (n, A) = (2, big), (256, tiny) */
    double mb = t_mvc_big - t_empty, mt = t_mvc_tiny - t_empty, sb = t_split_big - t_empty;
    double st = t_split_tiny - t_empty, det = 2 * tiny_px - 256 * big_px;
    c->mvc_px = (2 * mt - 256 * mb) / det * 1e6;
    c->mvc_quad = (mb * tiny_px - mt * big_px) / det * 1e6;
    c->split_px = (2 * st - 256 * sb) / det * 1e6;
    c->grid_tri = ((t_grid - t_empty) * 1e6 - c->split_px * SIZE * SIZE) / (16.0 * qgl_mvcgrid_at(b->grid)->ntris);
    return 1;
}

static void run(qgl_context *ctx, struct qgl__costs *c)
{
    struct qgl__gl *gl = &ctx->gl;
    double t0 = now_ms();
    GLint mode = GL_RENDER;
    gl->GetIntegerv(GL_RENDER_MODE, &mode);
    bench b = {.ctx = ctx, .grid = grid_number(8), .deadline = t0 + BUDGET_MS};
    b.prog = qgl__program(ctx, NULL);
    if (mode != GL_RENDER || b.grid < 0 || !b.prog)
        return;
    b.st.xf.viewport[2] = b.st.xf.viewport[3] = SIZE;
    b.st.shade_model = GL_SMOOTH;
    saved s;
    enter(ctx, &s);
    GLuint fb = 0, rb = 0;
    gl->GenFramebuffers(1, &fb);
    gl->GenRenderbuffers(1, &rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, rb);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, SIZE, SIZE);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fb);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    qgl__verts v = {0};
    int ok = gl->CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE && measure(&b, &v, c);
    qgl__verts_free(&v);
    leave(ctx, &s);
    gl->DeleteFramebuffers(1, &fb);
    gl->DeleteRenderbuffers(1, &rb);
    c->warm_ms = b.warm;
    c->ms = now_ms() - t0 - b.warm;
    if (ok && c->ms <= BUDGET_MS)
        sane(c);
}

/* QUADGL_COSTS: four figures in nanoseconds; 1 when given (valid or not). */
static int given(struct qgl__costs *c)
{
    const char *s = secure_getenv("QUADGL_COSTS");
    if (!s)
        return 0;
    if (sscanf(s, "%lf,%lf,%lf,%lf", &c->mvc_quad, &c->mvc_px, &c->split_px, &c->grid_tri) == 4)
        sane(c);
    return 1;
}

void qgl__costs_given(qgl_context *ctx)
{
    static struct qgl__costs from_env;
    if (given(&from_env))
        ctx->costs = &from_env;
}

void qgl__calibrate(qgl_context *ctx)
{
    if (ctx->costs || ctx->shader_level != 150 || !ctx->has_vao || !have_entry_points(&ctx->gl))
        return;
    const char *r = (const char *)ctx->gl.GetString(GL_RENDERER), *ver = (const char *)ctx->gl.GetString(GL_VERSION);
    char name[192];
    snprintf(name, sizeof name, "%s | %s", r ? r : "?", ver ? ver : "?");
    pthread_mutex_lock(&cache_lock);
    for (int i = 0; i < ncache; i++)
        if (!strcmp(cache[i].renderer, name)) {
            ctx->costs = &cache[i].costs;
            pthread_mutex_unlock(&cache_lock);
            return;
        }
    pthread_mutex_unlock(&cache_lock);
    struct qgl__costs c = {0};
    run(ctx, &c);
    pthread_mutex_lock(&cache_lock);
    int slot = ncache < 8 ? ncache++ : 7;
    snprintf(cache[slot].renderer, sizeof cache[slot].renderer, "%s", name);
    cache[slot].costs = c;
    ctx->costs = &cache[slot].costs;
    pthread_mutex_unlock(&cache_lock);
}

int qgl__grid_cheaper(const qgl_context *ctx, double area_px, int g)
{
    const struct qgl__costs *c = ctx->costs;
    const qgl_mvcgrid *grid = qgl_mvcgrid_at(g);
    if (!c || !c->valid || !grid)
        return 0;
    return c->grid_tri * grid->ntris + c->split_px * area_px < c->mvc_quad + c->mvc_px * area_px;
}

double qgl__split_saving(const qgl_context *ctx, double area_px)
{
    const struct qgl__costs *c = ctx->costs;
    if (!c || !c->valid)
        return INFINITY;
    return (c->mvc_px - c->split_px) * area_px;
}

QGL_API void qgl_gl_costs(const qgl_context *ctx, qgl_gl_costs_t *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (ctx)
        qgl__ready((qgl_context *)ctx);
    const struct qgl__costs *c = ctx ? ctx->costs : NULL;
    if (!c)
        return;
    out->valid = c->valid;
    out->ms = c->ms;
    out->warm_ms = c->warm_ms;
    out->mvc_quad_ns = c->mvc_quad;
    out->mvc_px_ns = c->mvc_px;
    out->split_px_ns = c->split_px;
    out->grid_tri_ns = c->grid_tri;
}
