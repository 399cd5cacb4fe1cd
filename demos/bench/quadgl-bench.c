/* quadgl-bench: speed against error of every quad rendering method on the papers' scenes.
 *
 * For each scene x method: the median time of an attribute render over repeats, Mpixel/s
 * (fragments written per second), the RMS and max error against the exact reference in the
 * scene's unit, the crease measure and the change under rotating the corner order. Prints
 * a Markdown table, a throughput line for mvc against split02 from the same run (one
 * full-screen quad at 1024^2 by default) with the machine's division throughput as the
 * arithmetic limit, a Pareto summary and the view drift of mvc against the view-invariant
 * methods; optionally --csv, --plot (gnuplot), --sheet (images and error heat maps) and
 * --drift-sheet (one quad from four viewpoints with its drift). Single-threaded by design: the figures are per core. */
#include "bench.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef QGL_HAVE_IMAGES
#include "qgl_image.h"
#endif

#ifndef QGL_SCENE_DIR
#define QGL_SCENE_DIR "data/scenes"
#endif

#define MAX_SCENES 64
#define MAX_METHODS 64

static const char *full_methods = "split02,split13,mvc,mvc64,bilinear:2,bilinear:4,bilinear:8,bilinear:16,"
                                  "bilinear:32,adaptive:area=800,adaptive,adaptive:q=1e-4,t=1e-5,area=50,"
                                  "invbilinear,projective,exact,mvcplane,mvcpatch,invbilinearplane,mvcgrid:2,mvcgrid:4,"
                                  "mvcgrid:8,mvcgrid:16";
static const char *quick_methods = "split02,split13,mvc,mvc64,bilinear:2,bilinear:8,adaptive,invbilinear,"
                                   "projective,exact,mvcplane,mvcpatch,mvcgrid:4";
static const char *sheet_columns[] = {"split02", "split13", "mvc", "bilinear:8", "adaptive",
                                      "invbilinear", "projective", "mvcgrid:4", "exact"};

typedef struct options {
    int quick, size, repeats, speed_size, thumb;
    const char *methods, *csv, *plot, *sheet, *drift_sheet;
    const char *scene_paths[MAX_SCENES];
    int nscene_paths;
} options;

static void usage(void)
{
    fprintf(stderr,
            "usage: quadgl-bench [--quick] [--size N] [--repeats N] [--speed-size N] [--methods LIST]\n"
            "                    [--csv FILE] [--plot FILE.png] [--sheet FILE.png] [--thumb N]\n"
            "                    [--drift-sheet FILE.png]\n"
            "                    [SCENE_FILE_OR_DIR...]   (default: %s)\n"
            "--drift-sheet: oliveira_trapezoid (else the first scene) from four viewpoints, mvc and\n"
            "mvcplane, with the change against the head-on value as a heat map\n"
            "methods: comma-separated names as qgl_sw_method_parse takes them; adaptive's own\n"
            "parameters use commas too and run to the next name (e.g. adaptive:q=1e-4,t=1e-5,mvc)\n",
            QGL_SCENE_DIR);
}

static int parse_args(int argc, char **argv, options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int more = i + 1 < argc;
        if (!strcmp(a, "--quick"))
            o->quick = 1;
        else if (!strcmp(a, "--size") && more)
            o->size = atoi(argv[++i]);
        else if (!strcmp(a, "--repeats") && more)
            o->repeats = atoi(argv[++i]);
        else if (!strcmp(a, "--speed-size") && more)
            o->speed_size = atoi(argv[++i]);
        else if (!strcmp(a, "--thumb") && more)
            o->thumb = atoi(argv[++i]);
        else if (!strcmp(a, "--methods") && more)
            o->methods = argv[++i];
        else if (!strcmp(a, "--csv") && more)
            o->csv = argv[++i];
        else if (!strcmp(a, "--plot") && more)
            o->plot = argv[++i];
        else if (!strcmp(a, "--sheet") && more)
            o->sheet = argv[++i];
        else if (!strcmp(a, "--drift-sheet") && more)
            o->drift_sheet = argv[++i];
        else if (a[0] != '-' && o->nscene_paths < MAX_SCENES)
            o->scene_paths[o->nscene_paths++] = a;
        else
            return -1;
    }
    if (o->size < 0 || o->repeats < 0 || o->speed_size < 0 || o->thumb < 0)
        return -1;
    return 0;
}

/* Split a method list at commas, keeping adaptive's key=value pairs with their method. */
static int parse_methods(const char *list, qgl_sw_method_desc *m, char names[][64])
{
    int n = 0;
    char buf[1024], cur[256] = "";
    snprintf(buf, sizeof buf, "%s", list);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (cur[0] && strchr(tok, '=') && !strchr(tok, ':')) {
            size_t l = strlen(cur);
            snprintf(cur + l, sizeof cur - l, ",%s", tok);
            continue;
        }
        if (cur[0]) {
            if (n == MAX_METHODS || qgl_sw_method_parse(cur, &m[n]))
                return fprintf(stderr, "quadgl-bench: bad method '%s'\n", cur), -1;
            qgl_sw_method_format(&m[n], names[n], 64);
            n++;
        }
        snprintf(cur, sizeof cur, "%s", tok);
    }
    if (cur[0]) {
        if (n == MAX_METHODS || qgl_sw_method_parse(cur, &m[n]))
            return fprintf(stderr, "quadgl-bench: bad method '%s'\n", cur), -1;
        qgl_sw_method_format(&m[n], names[n], 64);
        n++;
    }
    return n;
}

static int has_suffix(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && !strcmp(s + a - b, suffix);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Expand directories into their *.scene files (sorted). */
static int collect_scenes(const options *o, char **out)
{
    int n = 0;
    const char *def[1] = {QGL_SCENE_DIR};
    const char *const *paths = o->nscene_paths ? o->scene_paths : def;
    int np = o->nscene_paths ? o->nscene_paths : 1;
    for (int i = 0; i < np; i++) {
        DIR *d = opendir(paths[i]);
        if (!d) {
            if (n < MAX_SCENES)
                out[n++] = strdup(paths[i]);
            continue;
        }
        int first = n;
        for (struct dirent *e; (e = readdir(d)) && n < MAX_SCENES;)
            if (has_suffix(e->d_name, ".scene")) {
                char p[1024];
                snprintf(p, sizeof p, "%s/%s", paths[i], e->d_name);
                out[n++] = strdup(p);
            }
        closedir(d);
        qsort(out + first, (size_t)(n - first), sizeof(char *), cmp_str);
    }
    return n;
}

static int load_scene(const char *path, const options *o, bench_scene *bs)
{
    char err[1024];
    qgl_sw_scene_load_desc ld = {0};
#ifdef QGL_HAVE_IMAGES
    ld.load_image = qgl_image_load_texture;
#endif
    memset(bs, 0, sizeof *bs);
    if (qgl_sw_scene_load(path, &ld, &bs->scene, err, sizeof err)) {
        fprintf(stderr, "quadgl-bench: %s\n", err);
        return -1;
    }
    bs->width = o->size ? o->size : bs->scene->width;
    bs->height = o->size ? o->size : bs->scene->height;
    for (int r = 0; r < 2; r++)
        if (qgl_sw_scene_arrays(bs->scene, r, &bs->clip[r], &bs->attr[r], &bs->object[r]))
            return -1;
    return bench_image_alloc(&bs->reference, bs->width, bs->height, bs->scene->nattr);
}

static void free_scene(bench_scene *bs)
{
    for (int r = 0; r < 2; r++) {
        free(bs->clip[r]);
        free(bs->attr[r]);
        free(bs->object[r]);
    }
    bench_image_free(&bs->reference);
    free(bs->ref_shaded);
    qgl_sw_scene_free(bs->scene);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int in_sheet(const char *name)
{
    for (size_t i = 0; i < sizeof sheet_columns / sizeof sheet_columns[0]; i++)
        if (!strcmp(sheet_columns[i], name))
            return 1;
    return 0;
}

/* One scene x method: timing, errors, crease, rotation, and sheet images. */
static int run_one(const bench_scene *bs, const qgl_sw_method_desc *m, const char *name, const options *o,
                   bench_result *res)
{
    double times[64];
    int reps = o->repeats > 64 ? 64 : o->repeats;
    bench_image img, rot;
    if (bench_image_alloc(&img, bs->width, bs->height, bs->scene->nattr) ||
        bench_image_alloc(&rot, bs->width, bs->height, bs->scene->nattr))
        return -1;
    memset(res, 0, sizeof *res);
    snprintf(res->scene, sizeof res->scene, "%s", bs->scene->name);
    snprintf(res->method, sizeof res->method, "%s", name);
    res->m = *m;
    for (int r = 0; r < reps; r++)
        times[r] = bench_render(bs, m, 0, r == reps - 1 ? &img : NULL, &res->fragments);
    qsort(times, (size_t)reps, sizeof times[0], cmp_double);
    res->ms = times[reps / 2];
    res->mpix_s = res->ms > 0 ? res->fragments / (res->ms * 1e3) : 0;
    double unit = bs->scene->unit_scale, rmax;
    bench_error(&img, &bs->reference, unit, &res->rms, &res->max);
    res->crease = bench_crease(bs, &img, unit);
    bench_render(bs, m, 1, &rot, NULL);
    bench_error(&rot, &img, unit, &res->rotation, &rmax);
    res->drift = bench_drift(bs, m);
    if (o->sheet && in_sheet(name)) {
        res->shaded = bench_shaded(bs, m);
        res->heat = bench_heat(&img, &bs->reference, unit);
    }
    bench_image_free(&img);
    bench_image_free(&rot);
    return 0;
}

/* ---- throughput: one full-screen non-planar quad, and the division limit ---- */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

#define DIV_N 4096

/* A fixed trip count, so the vectorizer takes it at -O2 as it takes the mvc kernel's loops. */
#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target_clones("avx2", "default")))
#endif
static void divide_lanes(float *restrict c, const float *restrict a, const float *restrict b)
{
    for (int k = 0; k < DIV_N; k++)
        c[k] = a[k] / b[k];
}

/* Seconds per float division at full SIMD throughput (the same clones as the mvc kernel). */
static double division_time(void)
{
    enum { N = DIV_N, REPS = 2000 };
    static float a[N], b[N], c[N];
    for (int k = 0; k < N; k++) {
        a[k] = 1.0f + k * 1e-3f;
        b[k] = 3.0f + k * 1e-4f;
    }
    double best = INFINITY;
    for (int trial = 0; trial < 5; trial++) {
        double t0 = now_s();
        for (int r = 0; r < REPS; r++) {
            divide_lanes(c, a, b);
            b[r & (N - 1)] += c[(r * 7) & (N - 1)] * 1e-9f;
        }
        double t = (now_s() - t0) / ((double)N * REPS);
        best = t < best ? t : best;
    }
    return best;
}

static double speed_of(const char *method, int size, int reps, long long *frags)
{
    const float clip[16] = {-1.05f, -1.05f, 0.1f, 1.0f, 1.43f, -1.3f, 0.2f, 1.3f,
                            0.8f,   0.84f,  0.3f, 0.8f, -1.21f, 1.1f, 0.4f, 1.1f};
    const float attr[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    qgl_sw_fb_desc fd = {.width = size, .height = size, .channels = 2};
    qgl_sw_fb *fb = qgl_sw_fb_create(&fd);
    qgl_sw_draw_desc d = {.nquads = 1, .nattr = 2, .clip = clip, .attr = attr};
    if (!fb || qgl_sw_method_parse(method, &d.method)) {
        qgl_sw_fb_destroy(fb);
        return -1;
    }
    double times[64];
    reps = reps < 1 ? 1 : reps > 64 ? 64 : reps;
    for (int r = 0; r < reps; r++) {
        qgl_sw_stats st = {0};
        qgl_sw_fb_clear(fb, NULL, 1.0f);
        double t0 = now_s();
        qgl_sw_draw(fb, &d, &st);
        times[r] = now_s() - t0;
        *frags = st.fragments;
    }
    qgl_sw_fb_destroy(fb);
    qsort(times, (size_t)reps, sizeof times[0], cmp_double);
    return times[reps / 2];
}

static void throughput(int size, int reps)
{
    static const char *methods[] = {"mvc", "split02", "split13", "mvc64", "exact"};
    double mp[5];
    printf("\n## Throughput: one full-screen non-planar quad, %dx%d, 2 attributes, one core\n\n", size, size);
    printf("| method | ms | Mpix/s |\n|---|---:|---:|\n");
    for (int i = 0; i < 5; i++) {
        long long f = 0;
        double t = speed_of(methods[i], size, reps, &f);
        mp[i] = t > 0 ? f / t * 1e-6 : 0;
        printf("| %s | %.2f | %.1f |\n", methods[i], t * 1e3, mp[i]);
    }
    double tdiv = division_time();
    /* per pixel: 4 square roots, 4 divisions for t_i, 4 for nu_i, 2 for the normalization
     * and depth; a square root costs about a division on current cores */
    double limit = 1e-6 / (14 * tdiv);
    printf("\nmvc %.1f Mpix/s vs split02 %.1f Mpix/s (same run, ratio %.2f).\n", mp[0], mp[1], mp[0] / mp[1]);
    printf("Arithmetic limit: 14 divisions/square roots per pixel at %.3f ns per SIMD-lane division "
           "= %.0f Mpix/s; mvc reaches %.0f%% of it.\n",
           tdiv * 1e9, limit, 100 * mp[0] / limit);
}

/* ---- Pareto summary: mvc against the subdivisions at equal time ---- */

static void pareto(const bench_result *r, int n, const bench_scene *scenes, int nscenes)
{
    printf("\n## mvc against the subdivisions (bilinear:N, adaptive)\n\n");
    printf("| scene | mvc ms | mvc RMS | dominated by | fastest subdivision with RMS <= mvc (time x) "
           "| best subdivision RMS at time <= mvc (error x) |\n|---|---:|---:|---|---|---|\n");
    for (int s = 0; s < nscenes; s++) {
        const char *name = scenes[s].scene->name;
        const bench_result *mvc = NULL;
        for (int i = 0; i < n; i++)
            if (!strcmp(r[i].scene, name) && !strcmp(r[i].method, "mvc"))
                mvc = &r[i];
        if (!mvc)
            continue;
        const bench_result *fast = NULL, *best = NULL;
        char dom[256] = "";
        for (int i = 0; i < n; i++) {
            const bench_result *x = &r[i];
            if (strcmp(x->scene, name) || (strncmp(x->method, "bilinear", 8) && strncmp(x->method, "adaptive", 8)))
                continue;
            if (x->ms <= mvc->ms && x->rms <= mvc->rms) {
                size_t l = strlen(dom);
                snprintf(dom + l, sizeof dom - l, "%s%s", l ? ", " : "", x->method);
            }
            if (x->rms <= mvc->rms && (!fast || x->ms < fast->ms))
                fast = x;
            if (x->ms <= mvc->ms && (!best || x->rms < best->rms))
                best = x;
        }
        char fs[96] = "none", bs[96] = "none";
        if (fast)
            snprintf(fs, sizeof fs, "%s (%.2fx)", fast->method, fast->ms / mvc->ms);
        if (best)
            snprintf(bs, sizeof bs, "%s (%.2fx)", best->method, mvc->rms > 0 ? best->rms / mvc->rms : 0);
        printf("| %s | %.3f | %.4g | %s | %s | %s |\n", name, mvc->ms, mvc->rms, dom[0] ? dom : "nothing", fs, bs);
    }
}

/* ---- view drift: the screen-space weights against the view-invariant ones ---- */

static const bench_result *result_of(const bench_result *r, int n, const char *scene, const char *method)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(r[i].scene, scene) && !strcmp(r[i].method, method))
            return &r[i];
    return NULL;
}

/* Every quad of the scene planar (relative 1e-6, the planner's test). */
static int scene_planar(const qgl_sw_scene *s)
{
    for (int q = 0; q < s->nquads; q++) {
        double p[4][3];
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                p[i][k] = s->pos[3 * s->quad[4 * q + i] + k];
        if (!qgl_is_planar(p, 1e-6))
            return 0;
    }
    return 1;
}

/* Per scene: mvc's drift beside mvcplane's and mvcpatch's, and the target for planar quads
 * (half an 8-bit level, 1/64 texel: float rounding only). */
static void drift_summary(const bench_result *r, int n, const bench_scene *scenes, int nscenes)
{
    static const char *const cols[] = {"mvc", "mvcplane", "mvcpatch", "split02", "exact"};
    enum { NCOLS = sizeof cols / sizeof cols[0] };
    printf("\n## View drift: largest change at fixed surface points, head-on to 80 degrees\n\n");
    printf("| scene | quads | unit | mvc | mvcplane | mvcpatch | split02 | exact | target (planar) |\n"
           "|---|---|---|---:|---:|---:|---:|---:|---|\n");
    for (int s = 0; s < nscenes; s++) {
        const qgl_sw_scene *sc = scenes[s].scene;
        int planar = scene_planar(sc), levels = !strcmp(sc->unit, "levels");
        double target = levels ? 0.5 : 1.0 / 64;
        printf("| %s | %s | %s |", sc->name, planar ? "planar" : "non-planar", sc->unit);
        for (int c = 0; c < NCOLS; c++) {
            const bench_result *x = result_of(r, n, sc->name, cols[c]);
            if (x)
                printf(" %.3g |", x->drift);
            else
                printf(" |");
        }
        const bench_result *p = result_of(r, n, sc->name, "mvcplane");
        if (planar && p)
            printf(" < %.3g: %s |\n", target, p->drift < target ? "met" : "MISSED");
        else
            printf(" |\n");
    }
}

/* The drift picture's scene: Oliveira's textured trapezoid when it is loaded, else the first. */
static const bench_scene *drift_scene(const bench_scene *scenes, int n)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(scenes[i].scene->name, "oliveira_trapezoid"))
            return &scenes[i];
    return &scenes[0];
}

/* ---- the mean value grid against per-pixel mvc ---- */

/* Each mvcgrid:N result against mvc rendered again here (the same weights per pixel): the
 * grid's own error, beside its error against exact and both times from the main table. */
static void grid_report(const bench_result *r, int n, const bench_scene *scenes, int nscenes)
{
    printf("\n## mvcgrid (exact weights at the grid's vertices, linear between) against per-pixel mvc\n\n");
    printf("| scene | method | ms | mvc ms | max vs mvc | RMS vs mvc | RMS vs exact | mvc RMS vs exact |\n"
           "|---|---|---:|---:|---:|---:|---:|---:|\n");
    for (int s = 0; s < nscenes; s++) {
        const bench_scene *bs = &scenes[s];
        const bench_result *mvc = NULL;
        for (int i = 0; i < n; i++)
            if (!strcmp(r[i].scene, bs->scene->name) && !strcmp(r[i].method, "mvc"))
                mvc = &r[i];
        bench_image ref, img;
        if (!mvc || bench_image_alloc(&ref, bs->width, bs->height, bs->scene->nattr))
            continue;
        bench_render(bs, &mvc->m, 0, &ref, NULL);
        for (int i = 0; i < n; i++) {
            const bench_result *x = &r[i];
            if (strcmp(x->scene, bs->scene->name) || strncmp(x->method, "mvcgrid", 7) ||
                bench_image_alloc(&img, bs->width, bs->height, bs->scene->nattr))
                continue;
            double rms, max;
            bench_render(bs, &x->m, 0, &img, NULL);
            bench_error(&img, &ref, bs->scene->unit_scale, &rms, &max);
            printf("| %s | %s | %.3f | %.3f | %.4g | %.4g | %.4g | %.4g |\n", bs->scene->name, x->method, x->ms,
                   mvc->ms, max, rms, x->rms, mvc->rms);
            bench_image_free(&img);
        }
        bench_image_free(&ref);
    }
}

int main(int argc, char **argv)
{
    options o = {.repeats = 0};
    if (parse_args(argc, argv, &o)) {
        usage();
        return 2;
    }
    if (!o.size)
        o.size = o.quick ? 128 : 0;
    if (!o.repeats)
        o.repeats = o.quick ? 1 : 5;
    if (!o.speed_size)
        o.speed_size = o.quick ? 256 : 1024;
    if (!o.thumb)
        o.thumb = 128;
    qgl_sw_method_desc methods[MAX_METHODS];
    char names[MAX_METHODS][64];
    int nm = parse_methods(o.methods ? o.methods : o.quick ? quick_methods : full_methods, methods, names);
    char *paths[MAX_SCENES];
    int np = collect_scenes(&o, paths);
    if (nm <= 0 || np <= 0) {
        fprintf(stderr, "quadgl-bench: no %s\n", nm <= 0 ? "methods" : "scenes");
        return 2;
    }
    qgl_sw_method_desc exact = {.method = QGL_SW_EXACT};
    bench_scene *scenes = calloc((size_t)np, sizeof *scenes);
    bench_result *res = calloc((size_t)np * (size_t)nm, sizeof *res);
    int ns = 0, nr = 0, status = 0;
    for (int s = 0; s < np; s++) {
        if (load_scene(paths[s], &o, &scenes[ns])) {
            status = 1;
            continue;
        }
        bench_scene *bs = &scenes[ns++];
        bench_render(bs, &exact, 0, &bs->reference, NULL);
        for (int m = 0; m < nm; m++) {
            fprintf(stderr, "\r[%3d/%3d] %-22s %-40s", s * nm + m + 1, np * nm, bs->scene->name, names[m]);
            fflush(stderr);
            if (run_one(bs, &methods[m], names[m], &o, &res[nr]) == 0)
                nr++;
        }
    }
    fprintf(stderr, "\r%90s\r", "");
    printf("# quadgl-bench: %d scenes x %d methods, %s, median of %d\n\n", ns, nm,
           o.size ? "size override" : "scene sizes", o.repeats);
    bench_table(res, nr, scenes, ns);
    throughput(o.speed_size, o.repeats < 3 ? 3 : o.repeats);
    pareto(res, nr, scenes, ns);
    drift_summary(res, nr, scenes, ns);
    grid_report(res, nr, scenes, ns);
    if (o.csv && bench_csv(o.csv, res, nr))
        status = 1;
    if (o.plot && bench_plot(o.plot, res, nr, scenes, ns))
        status = 1;
    if (o.drift_sheet && ns > 0 && bench_drift_sheet(o.drift_sheet, drift_scene(scenes, ns), 256))
        status = 1;
    if (o.sheet && bench_sheet(o.sheet, res, nr, scenes, ns, sheet_columns,
                               (int)(sizeof sheet_columns / sizeof sheet_columns[0]), o.thumb))
        status = 1;
    for (int i = 0; i < nr; i++) {
        free(res[i].shaded);
        free(res[i].heat);
    }
    for (int s = 0; s < ns; s++)
        free_scene(&scenes[s]);
    for (int s = 0; s < np; s++)
        free(paths[s]);
    free(res);
    free(scenes);
    return status;
}
