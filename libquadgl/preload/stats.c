/* stats.c: what quadgl did, for the user: QUADGL_STATS and QUADGL_STATS_INTERVAL.
 *
 * Each context's GL path counts its quads by path, its draws and its buffer uploads
 * (qgl_gl_stats); the library adds them into process-wide atomic totals at every frame (the
 * swap) and when the context goes, and counts the quads it replays itself directly there. With
 * QUADGL_STATS=1 one line goes to stderr at exit, and also when the program is ended by
 * SIGINT, SIGTERM or SIGHUP: most interactive programs and every screensaver end that way,
 * not by exit(). The handler is installed only for signals whose action is the default one,
 * so a program's own handler is never displaced; it formats the totals itself (no stdio, no
 * locks, no allocation: only async-signal-safe calls), writes them with write(2) and
 * re-raises the signal with its default action, so the program still dies of it. What the
 * current frame drew so far on the signalled thread is added from its context's live counters.
 * QUADGL_STATS_INTERVAL=SECONDS adds a line every interval, at a swap: frames per second,
 * quads by path, draws and the time spent in quadgl's drawing per frame (measured only then). */
#include "preload.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static uint64_t pl_totals[PL_ST_COUNT];

void pl_count_passthrough(uint64_t quads)
{
    __atomic_add_fetch(&pl_totals[PL_ST_QUADS], quads, __ATOMIC_RELAXED);
    __atomic_add_fetch(&pl_totals[PL_ST_PASS], quads, __ATOMIC_RELAXED);
}

/* A context's GL path counters, in the order of the totals. */
static void pl_ctx_counts(const pl_ctx *x, uint64_t out[PL_ST_COUNT])
{
    qgl_gl_stats_t st;
    memset(out, 0, PL_ST_COUNT * sizeof *out);
    if (!x->qgl)
        return;
    qgl_gl_stats(x->qgl, &st);
    out[PL_ST_QUADS] = st.quads;
    out[PL_ST_MVC] = st.mvc;
    out[PL_ST_SPLIT] = st.split;
    out[PL_ST_SUBDIV] = st.subdiv + st.fallback;
    out[PL_ST_PASS] = st.passthrough;
    out[PL_ST_DRAWS] = st.draws;
    out[PL_ST_UPLOADS] = st.uploads;
}

void pl_stats_publish(pl_ctx *x)
{
    uint64_t now[PL_ST_COUNT];
    pl_ctx_counts(x, now);
    for (int k = 0; k < PL_ST_COUNT; k++) {
        if (k == PL_ST_FRAMES || k == PL_ST_NS)
            continue;
        __atomic_add_fetch(&pl_totals[k], now[k] - x->published[k], __ATOMIC_RELAXED);
        x->published[k] = now[k];
    }
}

void pl_stats_totals(uint64_t out[PL_ST_COUNT])
{
    for (int k = 0; k < PL_ST_COUNT; k++)
        out[k] = __atomic_load_n(&pl_totals[k], __ATOMIC_RELAXED);
}

/* ---- the line -------------------------------------------------------------------------------- */

static char *pl_put(char *p, const char *s)
{
    while (*s)
        *p++ = *s++;
    return p;
}

static char *pl_put_u64(char *p, uint64_t v)
{
    char digits[24];
    int n = 0;
    do
        digits[n++] = (char)('0' + v % 10);
    while ((v /= 10) != 0);
    while (n)
        *p++ = digits[--n];
    return p;
}

/* The final line into buf (at least 256 bytes), with only async-signal-safe work. */
static size_t pl_format(char *buf, const uint64_t t[PL_ST_COUNT])
{
    static const struct {
        const char *label;
        int k;
    } fields[] = {{" quads: mvc=", PL_ST_MVC}, {", split=", PL_ST_SPLIT}, {", subdiv=", PL_ST_SUBDIV},
                  {", passthrough=", PL_ST_PASS}, {", draws=", PL_ST_DRAWS}, {", list uploads=", PL_ST_UPLOADS},
                  {", frames=", PL_ST_FRAMES}};
    char *p = pl_put(buf, "quadgl: ");
    p = pl_put_u64(p, t[PL_ST_QUADS]);
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
        p = pl_put_u64(pl_put(p, fields[i].label), t[fields[i].k]);
    *p++ = '\n';
    return (size_t)(p - buf);
}

static int pl_printed;

static void pl_write_all(const char *buf, size_t n)
{
    while (n) {
        ssize_t w = write(2, buf, n);
        if (w <= 0)
            return;
        buf += w;
        n -= (size_t)w;
    }
}

static void pl_print_at_exit(void)
{
    char buf[256];
    uint64_t t[PL_ST_COUNT];
    if (__atomic_exchange_n(&pl_printed, 1, __ATOMIC_ACQ_REL))
        return;
    pl_ctx_publish_all();
    pl_stats_totals(t);
    pl_write_all(buf, pl_format(buf, t));
}

static void pl_on_signal(int sig)
{
    char buf[256];
    uint64_t t[PL_ST_COUNT], now[PL_ST_COUNT];
    pl_ctx *x = pl_tls_ctx;
    if (!__atomic_exchange_n(&pl_printed, 1, __ATOMIC_ACQ_REL)) {
        pl_stats_totals(t);
        if (x) {
            pl_ctx_counts(x, now);
            for (int k = 0; k < PL_ST_COUNT; k++)
                if (k != PL_ST_FRAMES && k != PL_ST_NS)
                    t[k] += now[k] - x->published[k];
        }
        pl_write_all(buf, pl_format(buf, t));
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

static void pl_catch(int sig)
{
    struct sigaction old, sa;
    if (sigaction(sig, NULL, &old) != 0 || old.sa_handler != SIG_DFL || (old.sa_flags & SA_SIGINFO))
        return; /* the program's own handler, or ignored: not ours to change */
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = pl_on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND | SA_NODEFER;
    sigaction(sig, &sa, NULL);
}

void pl_stats_init(void)
{
    if (!pl_cfg.stats)
        return;
    atexit(pl_print_at_exit);
    pl_catch(SIGINT);
    pl_catch(SIGTERM);
    pl_catch(SIGHUP);
}

/* ---- time and the interval line ------------------------------------------------------------ */

static double pl_mono(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

uint64_t pl_clock_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

void pl_stats_spent(uint64_t ns)
{
    __atomic_add_fetch(&pl_totals[PL_ST_NS], ns, __ATOMIC_RELAXED);
}

void pl_stats_frame(pl_ctx *x)
{
    static double last_time;
    static uint64_t last[PL_ST_COUNT];
    static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
    __atomic_add_fetch(&pl_totals[PL_ST_FRAMES], 1, __ATOMIC_RELAXED);
    if (x)
        pl_stats_publish(x);
    if (!(pl_cfg.stats_interval > 0))
        return;
    double now = pl_mono();
    pthread_mutex_lock(&lock);
    if (last_time == 0) {
        last_time = now;
        pl_stats_totals(last);
    } else if (now - last_time >= pl_cfg.stats_interval) {
        uint64_t t[PL_ST_COUNT];
        pl_stats_totals(t);
        double frames = (double)(t[PL_ST_FRAMES] - last[PL_ST_FRAMES]), per = frames > 0 ? 1 / frames : 0;
#define PL_D(k) ((double)(t[k] - last[k]) * per)
        fprintf(stderr,
                "quadgl: %.1f fps, per frame: %.0f quads (mvc %.0f, split %.0f, subdiv %.0f, passthrough %.0f), "
                "%.1f draws, %.2f ms in quadgl\n",
                frames / (now - last_time), PL_D(PL_ST_QUADS), PL_D(PL_ST_MVC), PL_D(PL_ST_SPLIT), PL_D(PL_ST_SUBDIV),
                PL_D(PL_ST_PASS), PL_D(PL_ST_DRAWS), PL_D(PL_ST_NS) * 1e-6);
#undef PL_D
        memcpy(last, t, sizeof t);
        last_time = now;
    }
    pthread_mutex_unlock(&lock);
}
