/* control.c: the preload library's settings, its log and the statistics line at exit.
 *
 * Settings come from the environment once, in the library constructor, which does nothing
 * else (no GL is touched before the program makes a context current): QUADGL_METHOD
 * (auto | mvc | split | subdiv | off, and replay: capture, then hand the quads back to the
 * driver unchanged, a check of the capture itself), QUADGL_STATS=1, QUADGL_LOG (warn | info
 * | debug) and QUADGL_TOLERANCE (pixels). They are read with secure_getenv, so a setuid
 * program ignores them. QUADGL_STATS and QUADGL_STATS_INTERVAL (seconds) are stats.c's. */
#include "preload.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

pl_config pl_cfg = {.capture = 1, .method = 0, .log_level = PL_LOG_WARN};

void pl_log(int level, const char *fmt, ...)
{
    va_list ap;
    if (level > pl_cfg.log_level)
        return;
    va_start(ap, fmt);
    fputs("quadgl: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

/* The counters of the statistics line, for programs and tests that want them without
 * parsing stderr: quads, mvc, split, subdiv, passthrough, draws, list uploads, frames. */
QGL_API void qgl_preload_stats(uint64_t out[8]);
QGL_API void qgl_preload_stats(uint64_t out[8])
{
    uint64_t t[PL_ST_COUNT];
    _Static_assert(PL_ST_FRAMES == 7, "the statistics line's counters come first, in its order");
    pl_ctx_publish_all();
    pl_stats_totals(t);
    for (int k = 0; k < 8; k++)
        out[k] = t[k];
}

static void pl_read_method(const char *s)
{
    static const struct {
        const char *name;
        int method;
    } names[] = {{"auto", 0}, {"mvc", 1}, {"split", 2}, {"subdiv", 3}, {"mvcplane", 4}};
    if (!s || !*s)
        return;
    if (strcmp(s, "off") == 0) {
        pl_cfg.capture = 0;
        return;
    }
    if (strcmp(s, "replay") == 0) {
        pl_cfg.replay = 1;
        return;
    }
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcmp(s, names[i].name) == 0) {
            pl_cfg.method = names[i].method;
            return;
        }
    pl_log(PL_LOG_WARN, "QUADGL_METHOD=%s unknown; using auto", s);
}

static void pl_read_log(const char *s)
{
    if (!s)
        return;
    if (strcmp(s, "info") == 0)
        pl_cfg.log_level = PL_LOG_INFO;
    else if (strcmp(s, "debug") == 0)
        pl_cfg.log_level = PL_LOG_DEBUG;
    else if (strcmp(s, "warn") != 0)
        pl_log(PL_LOG_WARN, "QUADGL_LOG=%s unknown; using warn", s);
}

static void pl_read_interval(const char *s)
{
    char *end;
    double v;
    if (!s || !*s)
        return;
    v = strtod(s, &end);
    if (*end || !(v > 0.0) || v > 1e6)
        pl_log(PL_LOG_WARN, "QUADGL_STATS_INTERVAL=%s is not a positive number of seconds; ignored", s);
    else
        pl_cfg.stats_interval = v;
}

static void pl_read_tolerance(const char *s)
{
    char *end;
    double v;
    if (!s || !*s)
        return;
    v = strtod(s, &end);
    if (*end || !(v > 0.0) || v > 1e6)
        pl_log(PL_LOG_WARN, "QUADGL_TOLERANCE=%s is not a positive number of pixels; ignored", s);
    else
        pl_cfg.tolerance = (float)v;
}

__attribute__((constructor)) static void pl_init(void)
{
    const char *stats = secure_getenv("QUADGL_STATS");
    pl_read_log(secure_getenv("QUADGL_LOG"));
    pl_read_method(secure_getenv("QUADGL_METHOD"));
    pl_read_tolerance(secure_getenv("QUADGL_TOLERANCE"));
    pl_read_interval(secure_getenv("QUADGL_STATS_INTERVAL"));
    pl_cfg.stats = (stats && *stats && strcmp(stats, "0") != 0) || pl_cfg.stats_interval > 0;
    pl_stats_init();
    pl_log(PL_LOG_INFO, "loaded (%s)", !pl_cfg.capture ? "off" : pl_cfg.replay ? "replay" : "capturing");
}
