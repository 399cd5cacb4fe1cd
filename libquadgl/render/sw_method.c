/* sw_method.c: method names, and parsing "name[:parameters]" into a method description.
 *
 * One table maps names to methods. Parameters follow a colon: bilinear and mvcgrid take the
 * number of subdivisions per side ("bilinear:16", "mvcgrid:8"); adaptive takes comma-separated key=value pairs
 * q (object threshold), t (texture threshold), area (pixels) and depth ("adaptive:q=1e-3").
 * Anything else is rejected whole, so a typo on a command line never runs a default. */
#include "sw_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const names[QGL_SW_METHOD_COUNT] = {
    [QGL_SW_MVC] = "mvc",
    [QGL_SW_MVC64] = "mvc64",
    [QGL_SW_SPLIT02] = "split02",
    [QGL_SW_SPLIT13] = "split13",
    [QGL_SW_BILINEAR] = "bilinear",
    [QGL_SW_ADAPTIVE] = "adaptive",
    [QGL_SW_INVBILINEAR] = "invbilinear",
    [QGL_SW_PROJECTIVE] = "projective",
    [QGL_SW_EXACT] = "exact",
    [QGL_SW_MVCPLANE] = "mvcplane",
    [QGL_SW_MVCPATCH] = "mvcpatch",
    [QGL_SW_INVBILINEARPLANE] = "invbilinearplane",
    [QGL_SW_MVCGRID] = "mvcgrid",
};

/* Methods taking a number of cells per side, and its default. */
static int cells_default(qgl_sw_method m)
{
    return m == QGL_SW_BILINEAR ? 8 : m == QGL_SW_MVCGRID ? 4 : 0;
}

const char *qgl_sw_method_name(qgl_sw_method m)
{
    return (unsigned)m < QGL_SW_METHOD_COUNT ? names[m] : "?";
}

static int parse_number(const char *s, size_t len, double *out)
{
    char buf[64];
    if (len == 0 || len >= sizeof buf)
        return -1;
    memcpy(buf, s, len);
    buf[len] = 0;
    char *end;
    errno = 0;
    *out = strtod(buf, &end);
    return *end || errno ? -1 : 0;
}

/* One "key=value" of adaptive's parameters. */
static int adaptive_pair(const char *s, size_t len, qgl_adaptive_params *p)
{
    const char *eq = memchr(s, '=', len);
    double v;
    if (!eq || parse_number(eq + 1, len - (size_t)(eq + 1 - s), &v) || !(v >= 0))
        return -1;
    size_t klen = (size_t)(eq - s);
    if (klen == 1 && s[0] == 'q')
        p->threshold_q = v;
    else if (klen == 1 && s[0] == 't')
        p->threshold_t = v;
    else if (klen == 4 && !memcmp(s, "area", 4))
        p->min_area_px = v;
    else if (klen == 5 && !memcmp(s, "depth", 5) && v == (int)v && v <= 30)
        p->max_depth = (int)v;
    else
        return -1;
    return 0;
}

static int parse_params(qgl_sw_method_desc *m, const char *params)
{
    if (cells_default(m->method)) {
        double n;
        if (parse_number(params, strlen(params), &n) || n != (int)n || n < 1 || n > 1024)
            return -1;
        m->n = (int)n;
        return 0;
    }
    if (m->method != QGL_SW_ADAPTIVE)
        return -1;
    while (*params) {
        const char *comma = strchr(params, ',');
        size_t len = comma ? (size_t)(comma - params) : strlen(params);
        if (adaptive_pair(params, len, &m->adaptive))
            return -1;
        params += len + (comma != NULL);
        if (comma && !*params)
            return -1;
    }
    return 0;
}

int qgl_sw_method_parse(const char *text, qgl_sw_method_desc *out)
{
    if (!out)
        return QGL_SW_EMETHOD;
    memset(out, 0, sizeof *out);
    if (!text)
        return QGL_SW_EMETHOD;
    const char *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : strlen(text);
    for (int m = 0; m < QGL_SW_METHOD_COUNT; m++) {
        if (strlen(names[m]) != len || memcmp(names[m], text, len))
            continue;
        out->method = (qgl_sw_method)m;
        out->n = cells_default(out->method);
        if (colon && parse_params(out, colon + 1)) {
            memset(out, 0, sizeof *out);
            return QGL_SW_EMETHOD;
        }
        return QGL_SW_OK;
    }
    return QGL_SW_EMETHOD;
}

int qgl_sw_method_format(const qgl_sw_method_desc *m, char *buf, size_t size)
{
    const char *name = qgl_sw_method_name(m->method);
    if (cells_default(m->method))
        return snprintf(buf, size, "%s:%d", name, m->n > 0 ? m->n : cells_default(m->method));
    if (m->method == QGL_SW_ADAPTIVE) {
        const qgl_adaptive_params *p = &m->adaptive;
        if (!p->threshold_q && !p->threshold_t && !p->min_area_px && !p->max_depth)
            return snprintf(buf, size, "%s", name);
        return snprintf(buf, size, "%s:q=%g,t=%g,area=%g,depth=%d", name, p->threshold_q ? p->threshold_q : 1e-3,
                        p->threshold_t ? p->threshold_t : 1e-4, p->min_area_px ? p->min_area_px : 200,
                        p->max_depth ? p->max_depth : 8);
    }
    return snprintf(buf, size, "%s", name);
}
