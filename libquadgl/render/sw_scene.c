/* sw_scene.c: scene files (camera, attributes, texture, quads, generators) and scene shading.
 *
 * A scene is a text file of one statement per line, '#' starting a comment; the grammar is
 * in data/scenes/README.md. Parsing is line by line into a growing vertex and quad list; each
 * keyword has one small handler, and every error message starts with "FILE:LINE:" so a bad
 * file points at its own line. Generators (sphere, heightfield) append vertices and quads as
 * if they had been written out; the sphere's pole rows are quads with a collapsed edge (two
 * corners at the exact same position), as a lat/long sphere modelled with quads has them.
 * The camera is GL's: gluPerspective / glOrtho times gluLookAt, column-major. */
#include "sw_internal.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_TOKENS 32
#define PI 3.14159265358979323846

typedef struct parser {
    qgl_sw_scene *s;
    const char *file;
    int line;
    char *err;
    size_t errlen;
    const qgl_sw_scene_load_desc *desc;
    double proj[16], view[16];
    int cap_v, cap_q;
    int have_attr;
    int attr_line, last_line; /* where 'attributes' was, the last statement */
} parser;

static int fail(parser *p, const char *fmt, ...)
{
    int n = snprintf(p->err, p->errlen, "%s:%d: ", p->file, p->line);
    if (n >= 0 && (size_t)n < p->errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->err + n, p->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return QGL_SW_EINVAL;
}

static int number(parser *p, const char *tok, double *out)
{
    char *end;
    errno = 0;
    *out = strtod(tok, &end);
    if (*end || errno || !isfinite(*out))
        return fail(p, "'%s' is not a finite number", tok);
    return 0;
}

static int integer(parser *p, const char *tok, int lo, int hi, int *out)
{
    double v;
    if (number(p, tok, &v))
        return QGL_SW_EINVAL;
    if (v != floor(v) || v < lo || v > hi)
        return fail(p, "'%s' must be an integer in [%d, %d]", tok, lo, hi);
    *out = (int)v;
    return 0;
}

static int numbers(parser *p, char **tok, int n, double *out)
{
    for (int i = 0; i < n; i++)
        if (number(p, tok[i], &out[i]))
            return QGL_SW_EINVAL;
    return 0;
}

static int expect(parser *p, int ntok, int want, const char *usage)
{
    if (ntok != want)
        return fail(p, "expected '%s' (%d values), got %d", usage, want - 1, ntok - 1);
    return 0;
}

/* ---- matrices (column-major, as GL) ---- */

static void mat_mul(const double a[16], const double b[16], double out[16])
{
    double r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double v = 0;
            for (int k = 0; k < 4; k++)
                v += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = v;
        }
    memcpy(out, r, sizeof r);
}

static void identity(double m[16])
{
    memset(m, 0, 16 * sizeof(double));
    m[0] = m[5] = m[10] = m[15] = 1;
}

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        for (int k = 0; k < 3; k++)
            v[k] /= l;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static int kw_lookat(parser *p, char **t, int n)
{
    double v[9];
    if (expect(p, n, 10, "lookat EX EY EZ CX CY CZ UX UY UZ") || numbers(p, t + 1, 9, v))
        return QGL_SW_EINVAL;
    double f[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, up[3] = {v[6], v[7], v[8]}, s[3], u[3];
    normalize3(f);
    cross3(f, up, s);
    normalize3(s);
    cross3(s, f, u);
    if (s[0] == 0 && s[1] == 0 && s[2] == 0)
        return fail(p, "lookat: the up vector is parallel to the view direction");
    double *m = p->view;
    identity(m);
    for (int k = 0; k < 3; k++) {
        m[k * 4 + 0] = s[k];
        m[k * 4 + 1] = u[k];
        m[k * 4 + 2] = -f[k];
    }
    for (int r = 0; r < 3; r++)
        m[12 + r] = -(m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2]);
    for (int k = 0; k < 3; k++)
        p->s->eye_dir[k] = -f[k];
    return 0;
}

static int kw_camera(parser *p, char **t, int n)
{
    double v[6];
    double *m = p->proj;
    memset(m, 0, 16 * sizeof(double));
    if (n >= 2 && !strcmp(t[1], "perspective")) {
        if (expect(p, n, 5, "camera perspective FOVY NEAR FAR") || numbers(p, t + 2, 3, v))
            return QGL_SW_EINVAL;
        if (!(v[0] > 0 && v[0] < 180 && v[1] > 0 && v[2] > v[1]))
            return fail(p, "camera perspective: need 0 < FOVY < 180 and 0 < NEAR < FAR");
        double f = 1 / tan(v[0] * PI / 360), aspect = (double)p->s->width / p->s->height;
        m[0] = f / aspect;
        m[5] = f;
        m[10] = (v[2] + v[1]) / (v[1] - v[2]);
        m[11] = -1;
        m[14] = 2 * v[2] * v[1] / (v[1] - v[2]);
        return 0;
    }
    if (n >= 2 && !strcmp(t[1], "ortho")) {
        if (expect(p, n, 8, "camera ortho LEFT RIGHT BOTTOM TOP NEAR FAR") || numbers(p, t + 2, 6, v))
            return QGL_SW_EINVAL;
        if (v[0] == v[1] || v[2] == v[3] || v[4] == v[5])
            return fail(p, "camera ortho: empty volume");
        m[0] = 2 / (v[1] - v[0]);
        m[5] = 2 / (v[3] - v[2]);
        m[10] = -2 / (v[5] - v[4]);
        m[12] = -(v[1] + v[0]) / (v[1] - v[0]);
        m[13] = -(v[3] + v[2]) / (v[3] - v[2]);
        m[14] = -(v[5] + v[4]) / (v[5] - v[4]);
        m[15] = 1;
        return 0;
    }
    return fail(p, "camera: expected 'perspective' or 'ortho'");
}

/* ---- geometry ---- */

static int grow(parser *p, int more_v, int more_q)
{
    qgl_sw_scene *s = p->s;
    if (s->nverts + more_v > p->cap_v) {
        int cap = (s->nverts + more_v) * 2;
        double *pos = realloc(s->pos, (size_t)cap * 3 * sizeof(double));
        if (pos)
            s->pos = pos;
        float *attr = realloc(s->attr, (size_t)cap * (size_t)(s->nattr ? s->nattr : 1) * sizeof(float));
        if (attr)
            s->attr = attr;
        if (!pos || !attr)
            return fail(p, "out of memory");
        p->cap_v = cap;
    }
    if (s->nquads + more_q > p->cap_q) {
        int cap = (s->nquads + more_q) * 2;
        int *q = realloc(s->quad, (size_t)cap * 4 * sizeof(int));
        if (!q)
            return fail(p, "out of memory");
        s->quad = q;
        p->cap_q = cap;
    }
    return 0;
}

static void add_vertex(parser *p, const double pos[3], const float *attr)
{
    qgl_sw_scene *s = p->s;
    memcpy(s->pos + 3 * s->nverts, pos, 3 * sizeof(double));
    memcpy(s->attr + (size_t)s->nverts * (size_t)s->nattr, attr, (size_t)s->nattr * sizeof(float));
    s->nverts++;
}

static void add_quad(parser *p, int a, int b, int c, int d)
{
    int *q = p->s->quad + 4 * p->s->nquads++;
    q[0] = a;
    q[1] = b;
    q[2] = c;
    q[3] = d;
}

static int need_attributes(parser *p)
{
    if (!p->have_attr)
        return fail(p, "'attributes' must come before any geometry");
    return 0;
}

static int kw_vertex(parser *p, char **t, int n)
{
    if (need_attributes(p))
        return QGL_SW_EINVAL;
    double v[3 + QGL_SW_MAX_ATTR];
    float a[QGL_SW_MAX_ATTR];
    int want = 4 + p->s->nattr;
    if (n != want)
        return fail(p, "vertex needs x y z and %d attribute values (%s), got %d values", p->s->nattr,
                    p->s->attr_kind, n - 1);
    if (numbers(p, t + 1, n - 1, v) || grow(p, 1, 0))
        return QGL_SW_EINVAL;
    for (int k = 0; k < p->s->nattr; k++)
        a[k] = (float)v[3 + k];
    add_vertex(p, v, a);
    return 0;
}

static int kw_quad(parser *p, char **t, int n)
{
    int idx[4];
    if (need_attributes(p) || expect(p, n, 5, "quad I0 I1 I2 I3"))
        return QGL_SW_EINVAL;
    for (int k = 0; k < 4; k++)
        if (integer(p, t[1 + k], 0, p->s->nverts - 1, &idx[k]))
            return fail(p, "quad: vertex index '%s' out of range (0..%d defined so far)", t[1 + k],
                        p->s->nverts - 1);
    if (grow(p, 0, 1))
        return QGL_SW_EINVAL;
    add_quad(p, idx[0], idx[1], idx[2], idx[3]);
    return 0;
}

/* Attributes of a generated vertex: uv from the parameters, or the unit normal. */
static void generated_attr(const qgl_sw_scene *s, double u, double v, const double normal[3], float *a)
{
    if (!strcmp(s->attr_kind, "uv")) {
        a[0] = (float)u;
        a[1] = (float)v;
    } else {
        for (int k = 0; k < 3; k++)
            a[k] = (float)(!strcmp(s->attr_kind, "color") ? 0.5 + 0.5 * normal[k] : normal[k]);
    }
}

static int kw_sphere(parser *p, char **t, int n)
{
    int stacks, slices;
    double r;
    if (need_attributes(p) || expect(p, n, 4, "sphere STACKS SLICES RADIUS") ||
        integer(p, t[1], 2, 2000, &stacks) || integer(p, t[2], 3, 2000, &slices) || number(p, t[3], &r))
        return QGL_SW_EINVAL;
    if (grow(p, (stacks + 1) * (slices + 1), stacks * slices))
        return QGL_SW_EINVAL;
    int base = p->s->nverts;
    for (int i = 0; i <= stacks; i++)
        for (int j = 0; j <= slices; j++) {
            /* the seam reuses column 0's angle and the poles are exact, so shared corners are
             * bit-identical (the mesh is closed) */
            double th = PI * i / stacks, ph = 2 * PI * (j % slices) / slices;
            double st = (i == 0 || i == stacks) ? 0 : sin(th), ct = i == 0 ? 1 : i == stacks ? -1 : cos(th);
            double nrm[3] = {st * cos(ph), -ct, -st * sin(ph)}, pos[3] = {r * nrm[0], r * nrm[1], r * nrm[2]};
            float a[QGL_SW_MAX_ATTR];
            generated_attr(p->s, (double)j / slices, (double)i / stacks, nrm, a);
            add_vertex(p, pos, a);
        }
    for (int i = 0; i < stacks; i++)
        for (int j = 0; j < slices; j++) {
            int v00 = base + i * (slices + 1) + j, v10 = v00 + slices + 1;
            add_quad(p, v00, v00 + 1, v10 + 1, v10);
        }
    return 0;
}

/* A bumpy height field z = h sin(2 pi x / size) cos(2 pi y / size) over a size x size square. */
static int kw_heightfield(parser *p, char **t, int n)
{
    int nx, ny;
    double size, h;
    if (need_attributes(p) || expect(p, n, 5, "heightfield NX NY SIZE HEIGHT") ||
        integer(p, t[1], 1, 2000, &nx) || integer(p, t[2], 1, 2000, &ny) || number(p, t[3], &size) ||
        number(p, t[4], &h))
        return QGL_SW_EINVAL;
    if (grow(p, (nx + 1) * (ny + 1), nx * ny))
        return QGL_SW_EINVAL;
    int base = p->s->nverts;
    double k = 2 * PI / size;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            double x = size * ((double)i / nx - 0.5), y = size * ((double)j / ny - 0.5);
            double pos[3] = {x, y, h * sin(k * x) * cos(k * y)};
            double nrm[3] = {-h * k * cos(k * x) * cos(k * y), h * k * sin(k * x) * sin(k * y), 1};
            normalize3(nrm);
            float a[QGL_SW_MAX_ATTR];
            generated_attr(p->s, (double)i / nx, (double)j / ny, nrm, a);
            add_vertex(p, pos, a);
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int v = base + j * (nx + 1) + i;
            add_quad(p, v, v + 1, v + nx + 2, v + nx + 1);
        }
    return 0;
}

/* ---- appearance ---- */

static int kw_attributes(parser *p, char **t, int n)
{
    static const struct {
        const char *kind, *unit;
        int n;
        double scale;
    } kinds[] = {{"uv", "texels", 2, 256}, {"color", "levels", 3, 255}, {"normal", "levels", 3, 255}};
    if (expect(p, n, 2, "attributes uv|color|normal"))
        return QGL_SW_EINVAL;
    if (p->s->nverts)
        return fail(p, "'attributes' must come before any geometry");
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
        if (!strcmp(t[1], kinds[i].kind)) {
            snprintf(p->s->attr_kind, sizeof p->s->attr_kind, "%s", kinds[i].kind);
            snprintf(p->s->unit, sizeof p->s->unit, "%s", kinds[i].unit);
            p->s->nattr = kinds[i].n;
            p->s->unit_scale = kinds[i].scale;
            p->s->shading = i == 0 ? QGL_SW_SHADE_TEXTURE : i == 1 ? QGL_SW_SHADE_COLOR : QGL_SW_SHADE_PHONG;
            p->have_attr = 1;
            p->attr_line = p->line;
            return 0;
        }
    return fail(p, "unknown attribute kind '%s' (uv, color or normal)", t[1]);
}

static void dirname_of(const char *path, char *dir, size_t n)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(dir, n, ".");
        return;
    }
    snprintf(dir, n, "%.*s", (int)(slash - path), path);
}

static int kw_texture(parser *p, char **t, int n)
{
    qgl_sw_texture *tex = &p->s->texture;
    qgl_sw_texture_free(tex);
    if (n >= 2 && !strcmp(t[1], "checker")) {
        int size, checks;
        if (expect(p, n, 4, "texture checker SIZE CHECKS") || integer(p, t[2], 1, 8192, &size) ||
            integer(p, t[3], 1, 8192, &checks))
            return QGL_SW_EINVAL;
        if (qgl_sw_texture_checker(tex, size, checks, 0.15f, 0.95f))
            return fail(p, "out of memory");
        if (!strcmp(p->s->attr_kind, "uv"))
            p->s->unit_scale = size;
        return 0;
    }
    if (n >= 2 && !strcmp(t[1], "image")) {
        if (expect(p, n, 3, "texture image FILE"))
            return QGL_SW_EINVAL;
        if (!p->desc || !p->desc->load_image)
            return fail(p, "texture image: this program cannot read image files (built without OpenImageIO)");
        char dir[512], path[1024], msg[512] = "";
        dirname_of(p->file, dir, sizeof dir);
        if (t[2][0] == '/')
            snprintf(path, sizeof path, "%s", t[2]);
        else
            snprintf(path, sizeof path, "%s/%s", dir, t[2]);
        if (p->desc->load_image(p->desc->user, path, tex, msg, sizeof msg))
            return fail(p, "texture image '%s': %s", path, msg[0] ? msg : "cannot read");
        if (!strcmp(p->s->attr_kind, "uv"))
            p->s->unit_scale = tex->width > tex->height ? tex->width : tex->height;
        return 0;
    }
    return fail(p, "texture: expected 'checker SIZE CHECKS' or 'image FILE'");
}

static int kw_simple(parser *p, char **t, int n)
{
    qgl_sw_scene *s = p->s;
    if (!strcmp(t[0], "name")) {
        if (expect(p, n, 2, "name NAME"))
            return QGL_SW_EINVAL;
        snprintf(s->name, sizeof s->name, "%s", t[1]);
    } else if (!strcmp(t[0], "size")) {
        if (expect(p, n, 3, "size W H") || integer(p, t[1], 1, 16384, &s->width) ||
            integer(p, t[2], 1, 16384, &s->height))
            return QGL_SW_EINVAL;
    } else if (!strcmp(t[0], "units")) {
        if (expect(p, n, 3, "units NAME SCALE") || number(p, t[2], &s->unit_scale))
            return QGL_SW_EINVAL;
        snprintf(s->unit, sizeof s->unit, "%s", t[1]);
    } else if (!strcmp(t[0], "filter")) {
        if (expect(p, n, 2, "filter nearest|bilinear"))
            return QGL_SW_EINVAL;
        if (strcmp(t[1], "nearest") && strcmp(t[1], "bilinear"))
            return fail(p, "filter: expected 'nearest' or 'bilinear', got '%s'", t[1]);
        s->filter = strcmp(t[1], "nearest") ? QGL_SW_FILTER_BILINEAR : QGL_SW_FILTER_NEAREST;
    } else if (!strcmp(t[0], "light")) {
        if (expect(p, n, 4, "light X Y Z") || numbers(p, t + 1, 3, s->light))
            return QGL_SW_EINVAL;
        normalize3(s->light);
    } else if (!strcmp(t[0], "cull")) {
        if (expect(p, n, 2, "cull back|none") || (strcmp(t[1], "back") && strcmp(t[1], "none")))
            return fail(p, "cull: expected 'back' or 'none'");
        s->cull_back = !strcmp(t[1], "back");
    } else {
        return 1;
    }
    return 0;
}

static int statement(parser *p, char **t, int n)
{
    static const struct {
        const char *kw;
        int (*fn)(parser *, char **, int);
    } table[] = {{"camera", kw_camera},         {"lookat", kw_lookat},   {"attributes", kw_attributes},
                 {"texture", kw_texture},       {"vertex", kw_vertex},   {"quad", kw_quad},
                 {"sphere", kw_sphere},         {"heightfield", kw_heightfield}};
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (!strcmp(t[0], table[i].kw))
            return table[i].fn(p, t, n);
    int r = kw_simple(p, t, n);
    if (r == 1)
        return fail(p, "unknown keyword '%s'", t[0]);
    return r;
}

static int split_line(char *line, char **tok)
{
    char *hash = strchr(line, '#'), *save = NULL;
    if (hash)
        *hash = 0;
    int n = 0;
    for (char *t = strtok_r(line, " \t\r\n", &save); t; t = strtok_r(NULL, " \t\r\n", &save)) {
        if (n == MAX_TOKENS)
            return -1;
        tok[n++] = t;
    }
    return n;
}

static void scene_defaults(qgl_sw_scene *s)
{
    s->width = s->height = 256;
    s->light[0] = s->light[1] = s->light[2] = 0.57735026918962573;
    s->eye_dir[2] = 1;
    s->unit_scale = 1;
    snprintf(s->unit, sizeof s->unit, "units");
}

static int parse_text(parser *p, char *text)
{
    char *tok[MAX_TOKENS];
    int line = 1;
    for (char *l = text; l; line++) {
        char *nl = strchr(l, '\n');
        if (nl)
            *nl = 0;
        p->line = line;
        int n = split_line(l, tok);
        if (n < 0)
            return fail(p, "too many values on one line (at most %d)", MAX_TOKENS - 1);
        if (n > 0 && statement(p, tok, n))
            return QGL_SW_EINVAL;
        if (n > 0)
            p->last_line = line;
        l = nl ? nl + 1 : NULL;
    }
    p->line = p->last_line;
    if (!p->s->nquads)
        return fail(p, "the scene has no quads");
    p->line = p->attr_line;
    if (p->s->shading == QGL_SW_SHADE_TEXTURE && !p->s->texture.texels)
        return fail(p, "uv attributes need a 'texture' line");
    mat_mul(p->proj, p->view, p->s->mvp);
    return 0;
}

int qgl_sw_scene_parse(const char *text, const char *name, const qgl_sw_scene_load_desc *desc,
                       qgl_sw_scene **out, char *err, size_t errlen)
{
    char dummy[8];
    if (!err || !errlen) {
        err = dummy;
        errlen = sizeof dummy;
    }
    err[0] = 0;
    if (!out || !text) {
        snprintf(err, errlen, "invalid argument");
        return QGL_SW_EINVAL;
    }
    *out = NULL;
    qgl_sw_scene *s = calloc(1, sizeof *s);
    char *copy = strdup(text);
    parser p = {.s = s, .file = name ? name : "<scene>", .err = err, .errlen = errlen, .desc = desc};
    if (!s || !copy) {
        free(s);
        free(copy);
        snprintf(err, errlen, "%s: out of memory", p.file);
        return QGL_SW_ENOMEM;
    }
    scene_defaults(s);
    snprintf(s->path, sizeof s->path, "%s", p.file);
    identity(p.proj);
    identity(p.view);
    int r = parse_text(&p, copy);
    free(copy);
    if (r) {
        qgl_sw_scene_free(s);
        return r;
    }
    if (!s->name[0]) {
        const char *base = strrchr(p.file, '/');
        snprintf(s->name, sizeof s->name, "%s", base ? base + 1 : p.file);
        char *dot = strrchr(s->name, '.');
        if (dot)
            *dot = 0;
    }
    *out = s;
    return 0;
}

int qgl_sw_scene_load(const char *path, const qgl_sw_scene_load_desc *desc, qgl_sw_scene **out, char *err,
                      size_t errlen)
{
    char dummy[8];
    if (!err || !errlen) {
        err = dummy;
        errlen = sizeof dummy;
    }
    if (out)
        *out = NULL;
    FILE *f = path ? fopen(path, "rb") : NULL;
    if (!f) {
        snprintf(err, errlen, "%s:0: cannot open: %s", path ? path : "(null)", strerror(errno));
        return QGL_SW_EINVAL;
    }
    size_t cap = 4096, len = 0;
    char *text = malloc(cap);
    for (size_t got; text && (got = fread(text + len, 1, cap - len - 1, f)) > 0;) {
        len += got;
        if (len + 1 == cap) {
            char *t = realloc(text, cap *= 2);
            if (!t) {
                free(text);
                text = NULL;
            } else {
                text = t;
            }
        }
    }
    fclose(f);
    if (!text) {
        snprintf(err, errlen, "%s:0: out of memory", path);
        return QGL_SW_ENOMEM;
    }
    text[len] = 0;
    if (strlen(text) != len) {
        free(text);
        snprintf(err, errlen, "%s:0: not a text file (NUL byte)", path);
        return QGL_SW_EINVAL;
    }
    int r = qgl_sw_scene_parse(text, path, desc, out, err, errlen);
    free(text);
    return r;
}

void qgl_sw_scene_free(qgl_sw_scene *s)
{
    if (!s)
        return;
    qgl_sw_texture_free(&s->texture);
    free(s->pos);
    free(s->attr);
    free(s->quad);
    free(s);
}

int qgl_sw_scene_arrays(const qgl_sw_scene *s, int rotate, float **clip, float **attr, float **object)
{
    if (!s || !clip || !attr || !object)
        return QGL_SW_EINVAL;
    size_t nq = (size_t)s->nquads;
    *clip = malloc(nq * 16 * sizeof(float));
    *attr = malloc(nq * 4 * (size_t)(s->nattr ? s->nattr : 1) * sizeof(float));
    *object = malloc(nq * 12 * sizeof(float));
    if (!*clip || !*attr || !*object) {
        free(*clip);
        free(*attr);
        free(*object);
        *clip = *attr = *object = NULL;
        return QGL_SW_ENOMEM;
    }
    const double *m = s->mvp;
    for (size_t q = 0; q < nq; q++)
        for (int i = 0; i < 4; i++) {
            int v = s->quad[q * 4 + (size_t)(((i + rotate) % 4 + 4) % 4)];
            const double *p = s->pos + 3 * v;
            for (int r = 0; r < 4; r++)
                (*clip)[(q * 4 + (size_t)i) * 4 + (size_t)r] =
                    (float)(m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
            for (int k = 0; k < 3; k++)
                (*object)[(q * 4 + (size_t)i) * 3 + (size_t)k] = (float)p[k];
            for (int k = 0; k < s->nattr; k++)
                (*attr)[(q * 4 + (size_t)i) * (size_t)s->nattr + (size_t)k] = s->attr[(size_t)v * (size_t)s->nattr + (size_t)k];
        }
    return QGL_SW_OK;
}

/* Blinn-Phong on the interpolated normal, re-normalized per pixel; two-sided. */
static void phong(const qgl_sw_scene *s, const float *n_in, int facing, float *out)
{
    double n[3] = {n_in[0], n_in[1], n_in[2]}, h[3];
    normalize3(n);
    if (facing < 0)
        for (int k = 0; k < 3; k++)
            n[k] = -n[k];
    for (int k = 0; k < 3; k++)
        h[k] = s->light[k] + s->eye_dir[k];
    normalize3(h);
    double diff = n[0] * s->light[0] + n[1] * s->light[1] + n[2] * s->light[2];
    double spec = n[0] * h[0] + n[1] * h[1] + n[2] * h[2];
    diff = diff > 0 ? diff : 0;
    spec = spec > 0 ? pow(spec, 40) : 0;
    static const double base[3] = {0.85, 0.55, 0.3};
    for (int k = 0; k < 3; k++)
        out[k] = (float)(0.08 + 0.75 * diff * base[k] + 0.5 * spec);
}

int qgl_sw_scene_shade(void *user, const float *attr, int nattr, int facing, float *out)
{
    const qgl_sw_scene *s = user;
    out[3] = 1;
    if (s->shading == QGL_SW_SHADE_TEXTURE && nattr >= 2) {
        qgl_sw_texture_sample(&s->texture, s->filter, attr[0], attr[1], out);
        out[3] = 1;
    } else if (s->shading == QGL_SW_SHADE_PHONG && nattr >= 3) {
        phong(s, attr, facing, out);
    } else {
        for (int k = 0; k < 3; k++)
            out[k] = k < nattr ? attr[k] : 0;
    }
    return 1;
}
