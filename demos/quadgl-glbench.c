/* quadgl-glbench: frame-time ratios of the GL layer against the driver's native split (OSMesa).
 *
 * Three targets of issue 4, each timed as the median of several frames (draw + glFinish; native
 * and qgl frames alternate) in one run, wall clock and process CPU time: a full-screen
 * non-affine quad at 1024^2 on the shader path; AUTO on a textured latitude/longitude sphere
 * and a height field with random corner colours (the worst case: every quad visibly non-affine)
 * and, for contrast, a flat slice with a smooth colour map (the split invisible); and many tiny
 * quads in immediate mode (1M vertices per frame). The full-screen quad, the sphere and the
 * height field are also drawn with the other weights (mvcplane, or mvc beside AUTO's
 * view-invariant ones) in the same run. Native frames call the driver's
 * glBegin/glVertex directly; ours call the qgl* twins. Usage: quadgl-glbench [frames [name]] (default 9 frames; name runs
 * only the cases whose title contains it, e.g. "mesh", for profiling). */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/osmesa.h>
#include <math.h>
#include <quadgl/quadgl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { W = 1024, H = 1024 };

typedef void (*frame_fn)(int native);

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof t[0], cmp);
    return t[n / 2];
}

/* Median wall and CPU milliseconds of native and qgl frames, taken alternately so that the
 * load of a shared machine weighs on both alike. CPU time counts every thread of the process
 * (llvmpipe's rasterizer threads too): it hardly moves when other processes compete for the
 * cores, so its ratio is the steadier figure there. */
typedef struct timing {
    double wall[2], cpu[2]; /* [0] native, [1] qgl */
} timing;

static void measure(frame_fn f, int frames, timing *out)
{
    double wall[2][64], cpu[2][64];
    f(1); /* warm-up: shader compilation, buffer growth */
    f(0);
    qgl_gl_flush(qgl_gl_current());
    glFinish();
    for (int i = 0; i < frames; i++)
        for (int k = 0; k < 2; k++) {
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glFinish();
            double t0 = now(), c0 = cpu_now();
            f(k == 0);
            if (k == 1)
                qgl_gl_flush(qgl_gl_current()); /* the end of a frame: quads gathered are drawn */
            glFinish();
            wall[k][i] = (now() - t0) * 1e3;
            cpu[k][i] = (cpu_now() - c0) * 1e3;
        }
    for (int k = 0; k < 2; k++) {
        out->wall[k] = median(wall[k], frames);
        out->cpu[k] = median(cpu[k], frames);
    }
}

#define B(native) ((native) ? glBegin : qglBegin)
#define E(native) ((native) ? glEnd : qglEnd)
#define C4(native) ((native) ? glColor4f : qglColor4f)
#define T2(native) ((native) ? glTexCoord2f : qglTexCoord2f)
#define V3(native) ((native) ? glVertex3f : qglVertex3f)
/* Before a GL call of our own: the qgl context is told to draw what it gathered. */
#define FLUSH(native) ((native) ? (void)0 : qgl_gl_flush(qgl_gl_current()))

static void ortho(void)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

static void perspective(void)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.6, 0.6, -0.6, 0.6, 1, 10);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glTranslatef(0, 0, -2.8f);
    glRotatef(-60, 1, 0, 0);
}

/* A full-screen quad whose colours are not affine (R, G, B, black corners). */
static void fullscreen(int native)
{
    static const float p[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    static const float c[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
    B(native)(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        C4(native)(c[i][0], c[i][1], c[i][2], 1);
        V3(native)(p[i][0], p[i][1], 0);
    }
    E(native)();
}

static void sphere_vertex(int native, int i, int j, int nu, int nv)
{
    double th = 2 * M_PI * i / nu, ph = M_PI * j / nv - M_PI / 2;
    T2(native)((float)i / nu * 4, (float)j / nv * 2);
    V3(native)((float)(cos(ph) * cos(th)), (float)(cos(ph) * sin(th)), (float)sin(ph));
}

/* Textured latitude/longitude sphere, 48 x 24 quads, white (the texture as it is: the colour
 * the cases before left current would modulate it, black after the full-screen quad's). */
static void sphere(int native)
{
    enum { NU = 48, NV = 24 };
    glEnable(GL_TEXTURE_2D);
    glEnable(GL_DEPTH_TEST);
    C4(native)(1, 1, 1, 1);
    B(native)(GL_QUADS);
    for (int j = 0; j < NV; j++)
        for (int i = 0; i < NU; i++) {
            sphere_vertex(native, i, j, NU, NV);
            sphere_vertex(native, i + 1, j, NU, NV);
            sphere_vertex(native, i + 1, j + 1, NU, NV);
            sphere_vertex(native, i, j + 1, NU, NV);
        }
    E(native)();
    FLUSH(native);
    glDisable(GL_TEXTURE_2D);
}

static float hash(int i, int j, int k)
{
    unsigned h = (unsigned)i * 73856093u ^ (unsigned)j * 19349663u ^ (unsigned)k * 83492791u;
    h = h * 2654435761u;
    return (float)(h >> 8 & 0xffff) / 65535.0f;
}

/* A 64 x 64 height field with random vertex colours, drawn as quad strips. */
static void mesh(int native)
{
    enum { N = 64 };
    glEnable(GL_DEPTH_TEST);
    for (int j = 0; j < N; j++) {
        B(native)(GL_QUAD_STRIP);
        for (int i = 0; i <= N; i++)
            for (int k = 0; k < 2; k++) {
                int jj = j + k;
                C4(native)(hash(i, jj, 0), hash(i, jj, 1), hash(i, jj, 2), 1);
                V3(native)(-1 + 2.0f * i / N, -1 + 2.0f * jj / N, 0.1f * sinf(i * 0.4f) * cosf(jj * 0.3f));
            }
        E(native)();
    }
}

/* A flat slice coloured by a smooth map of the position, as a visualisation colours a field:
 * over one quad the colours are nearly affine, and the split differs invisibly. */
static void slice(int native)
{
    enum { N = 64 };
    glEnable(GL_DEPTH_TEST);
    for (int j = 0; j < N; j++) {
        B(native)(GL_QUAD_STRIP);
        for (int i = 0; i <= N; i++)
            for (int k = 0; k < 2; k++) {
                float x = -1 + 2.0f * i / N, y = -1 + 2.0f * (j + k) / N;
                C4(native)(0.5f + 0.4f * sinf(2 * x), 0.5f + 0.4f * cosf(3 * y), 0.5f + 0.4f * sinf(x + y), 1);
                V3(native)(x, y, 0);
            }
        E(native)();
    }
}

/* 250 000 quads of about 1.5 x 1.5 pixels: 1M vertices in one glBegin/glEnd. */
static void tiny(int native)
{
    enum { NX = 500, NY = 500 };
    float sx = 2.0f / NX, sy = 2.0f / NY, q = 0.75f;
    B(native)(GL_QUADS);
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            float x = -1 + i * sx, y = -1 + j * sy;
            C4(native)(hash(i, j, 0), 0.5f, 0.2f, 1);
            V3(native)(x, y, 0);
            C4(native)(0.2f, hash(i, j, 1), 0.5f, 1);
            V3(native)(x + q * sx, y, 0);
            C4(native)(0.5f, 0.2f, hash(i, j, 2), 1);
            V3(native)(x + q * sx, y + q * sy, 0);
            C4(native)(1, 1, 1, 1);
            V3(native)(x, y + q * sy, 0);
        }
    E(native)();
}

static void make_texture(void)
{
    static unsigned char tex[256][256][4];
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) {
            int on = ((x / 16) ^ (y / 16)) & 1;
            tex[y][x][0] = (unsigned char)(on ? 230 : 40);
            tex[y][x][1] = (unsigned char)(on ? 200 : 60);
            tex[y][x][2] = (unsigned char)x;
            tex[y][x][3] = 255;
        }
    GLuint id;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 256, 256, 0, GL_RGBA, GL_UNSIGNED_BYTE, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

static const char *only; /* run only cases whose name contains this */

/* One frame of f in method m, read back (W * H * 4 bytes, caller frees). */
static unsigned char *frame_of(qgl_context *q, qgl_method m, frame_fn f)
{
    unsigned char *img = malloc((size_t)W * H * 4);
    qgl_gl_set_method(q, m);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    f(0);
    qgl_gl_flush(q);
    glFinish();
    if (img)
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, img);
    return img;
}

/* The method's picture against the per-fragment picture of the interpolant auto draws smooth
 * (the view-invariant weights, mvcplane): the largest difference in 8-bit levels, the values
 * more than one level apart (the budget is half a level before rounding, so one level is what
 * rounding alone can add) and the pixels not black in the method's picture (a comparison of
 * two black pictures holds nothing). */
static void against_mvc(qgl_context *q, qgl_method m, frame_fn f, int *worst, long *over, long *drawn)
{
    unsigned char *a = frame_of(q, m, f), *b = frame_of(q, QGL_METHOD_MVC_PLANE, f);
    *worst = 0, *over = 0, *drawn = 0;
    for (size_t i = 0; a && b && i < (size_t)W * H * 4; i++) {
        int d = abs(a[i] - b[i]);
        *worst = d > *worst ? d : *worst;
        *over += d > 1;
        *drawn += i % 4 == 0 && (a[i] | a[i + 1] | a[i + 2]);
    }
    free(a);
    free(b);
    qgl_gl_set_method(q, m);
}

static void report(const char *name, qgl_context *q, qgl_method method, frame_fn setup, frame_fn f, int frames,
                   double target)
{
    if (only && !strstr(name, only))
        return;
    qgl_gl_make_current(q);
    setup(0);
    qgl_gl_set_method(q, method);
    timing t;
    qgl_gl_reset_stats(q);
    measure(f, frames, &t);
    qgl_gl_stats_t st;
    qgl_gl_stats(q, &st);
    double per = (double)(frames + 1), ratio = t.wall[1] / t.wall[0];
    int worst = 0;
    long over = 0, drawn = 0;
    if (method == QGL_METHOD_AUTO)
        against_mvc(q, method, f, &worst, &over, &drawn);
    printf("%-36s native %7.2f ms  quadgl %7.2f ms  ratio %5.2f (target <= %.2f) %-6s cpu ratio %5.2f | per frame: "
           "mvc %.0f split %.0f grid %.0f fallback %.0f draws %.0f",
           name, t.wall[0], t.wall[1], ratio, target, ratio <= target ? "met" : "MISSED", t.cpu[1] / t.cpu[0],
           st.mvc / per, st.split / per, st.subdiv / per, st.fallback / per, st.draws / per);
    if (method == QGL_METHOD_AUTO)
        printf(" | vs mvcplane picture: max %d levels, %ld values over 1, %ld pixels drawn%s", worst, over, drawn,
               drawn ? "" : " (EMPTY: the comparison holds nothing)");
    printf("\n");
}

static void setup_ortho(int unused) { (void)unused, ortho(); }
static void setup_persp(int unused) { (void)unused, perspective(); }

int main(int argc, char **argv)
{
    int frames = argc > 1 ? atoi(argv[1]) : 9;
    frames = frames < 1 ? 1 : frames > 64 ? 64 : frames;
    only = argc > 2 ? argv[2] : NULL;
    static const int attr[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE, OSMESA_COMPAT_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    OSMesaContext osm = OSMesaCreateContextAttribs(attr, NULL);
    void *buf = malloc((size_t)W * H * 4);
    if (!osm || !buf || !OSMesaMakeCurrent(osm, buf, GL_UNSIGNED_BYTE, W, H)) {
        fprintf(stderr, "quadgl-glbench: no OSMesa compatibility context\n");
        return 1;
    }
    /* q gathers consecutive primitives (this program flushes before its own GL calls, as
     * the preload library can); q1 draws each primitive at its qglEnd */
    qgl_gl_desc d = {.get_proc = (void *(*)(const char *))OSMesaGetProcAddress, .assume_exclusive = 1};
    qgl_context *q = qgl_gl_create(&d);
    d.assume_exclusive = 0;
    qgl_context *q1 = qgl_gl_create(&d);
    if (!q || !q1) {
        fprintf(stderr, "quadgl-glbench: qgl_gl_create failed\n");
        return 1;
    }
    qgl_gl_make_current(q);
    glViewport(0, 0, W, H);
    make_texture();
    printf("%s, %dx%d, median of %d frames, shader level %d\n", (const char *)glGetString(GL_RENDERER), W, H,
           frames, qgl_gl_shader_level(q));
    qgl_gl_costs_t costs;
    qgl_gl_costs(q, &costs);
    printf("calibration: %s in %.1f ms (+ %.0f ms of first draws): shader path %.0f ns/quad + %.2f ns/px, split %.2f ns/px, grid %.0f ns/triangle\n",
           costs.valid ? "valid" : "INVALID (the planner keeps the shader path)", costs.ms, costs.warm_ms, costs.mvc_quad_ns,
           costs.mvc_px_ns, costs.split_px_ns, costs.grid_tri_ns);
    report("full-screen non-affine quad (mvc)", q, QGL_METHOD_MVC, setup_ortho, fullscreen, frames, 2.0);
    report("full-screen non-affine quad (mvcplane)", q, QGL_METHOD_MVC_PLANE, setup_ortho, fullscreen, frames, 2.0);
    report("full-screen non-affine quad (auto)", q, QGL_METHOD_AUTO, setup_ortho, fullscreen, frames, 2.0);
    report("sphere 48x24 textured (auto)", q, QGL_METHOD_AUTO, setup_persp, sphere, frames, 1.1);
    report("mesh 64x64 colour strips (auto)", q, QGL_METHOD_AUTO, setup_persp, mesh, frames, 1.1);
    report("mesh, one draw per strip (auto)", q1, QGL_METHOD_AUTO, setup_persp, mesh, frames, 1.1);
    report("colour-mapped slice 64x64 (auto)", q, QGL_METHOD_AUTO, setup_persp, slice, frames, 1.05);
    report("250k tiny quads, 1M vertices (auto)", q, QGL_METHOD_AUTO, setup_ortho, tiny, frames, 1.1);
    /* the screen-space weights on the same scenes, for AUTO's view-invariant ones above */
    report("sphere 48x24 textured (mvc)", q, QGL_METHOD_MVC, setup_persp, sphere, frames, 99);
    report("mesh 64x64 colour strips (mvc)", q, QGL_METHOD_MVC, setup_persp, mesh, frames, 99);
    qgl_gl_destroy(q);
    qgl_gl_destroy(q1);
    OSMesaDestroyContext(osm);
    free(buf);
    return 0;
}
