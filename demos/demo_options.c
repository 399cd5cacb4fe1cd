/* demo_options.c: quadgl-demo's command line and its help text (options and keys).
 *
 * A table maps each option to a small handler; options that take a value read the next
 * argument and check it fully (a number must be all digits, a method must be known), so
 * every mistake stops the program with a message that names the bad argument, the usage,
 * and exit code 2, before anything is drawn. */
#include <stdlib.h>
#include <string.h>

#include "demo_options.h"

#ifndef DEMO_SCENE_DIR
#define DEMO_SCENE_DIR "data/scenes"
#endif

static const char usage_text[] =
    "usage: quadgl-demo [OPTIONS]                   open a window (GLFW)\n"
    "       quadgl-demo --headless --out DIR [OPTIONS]  render every scene and method (OSMesa)\n";

static const char options_text[] =
    "\n"
    "Options:\n"
    "  -h, --help          this text\n"
    "  --list              list the scenes and methods, then exit\n"
    "  --headless          no window: render through OSMesa, write DIR/SCENE__METHOD.png,\n"
    "                      DIR/SCENE__METHOD__err.png (heat map against the reference),\n"
    "                      for auto also DIR/SCENE__auto__mvcplane.png (its weights per\n"
    "                      fragment, no split or grid) and __vs_mvcplane.png (the difference),\n"
    "                      and DIR/contact_sheet.png (scenes as rows, methods as columns)\n"
    "  --out DIR           output directory for --headless (created if missing)\n"
    "  --scenes DIR        scene files to load (default: the source tree's scenes)\n"
    "  --scene NAME        scene to start with; headless: the only scene rendered\n"
    "  --method M[,M...]   native, mvc, auto, subdiv, reference; window: the methods of the\n"
    "                      panels; headless: the columns (default: every available method)\n"
    "  --view V            window layout: single, split (native | mvc) or quad (2 x 2)\n"
    "  --size WxH          window size; headless: picture size (default: each scene's own)\n"
    "  --order K           rotate every quad's vertex order by K (0..3)\n"
    "  --wireframe         quad outlines on top (and the driver's diagonal for native)\n"
    "  --no-shading        show the raw interpolated attribute as colour\n"
    "  --frames N          window: quit after N frames\n"
    "  --screenshot FILE   window: save the last frame as PNG (read back before the swap)\n"
    "  --no-text           window: no on-screen text\n"
    "  --quiet             headless: no table on stdout\n"
    "\n"
    "Methods: native = plain glBegin(GL_QUADS), the driver's diagonal split (smooth when run\n"
    "  under `quadgl run`); mvc / auto / subdiv = the same calls through the GL helper's qgl*\n"
    "  API with that method; reference = the software renderer's exact ray/patch reference.\n"
    "\n"
    "Keys (window):\n"
    "  Right / Left, N / P   next / previous scene\n"
    "  1..9                  scene by number\n"
    "  M / Shift+M           next / previous method of the selected panel\n"
    "  Tab                   select the next panel\n"
    "  V                     layout: single, split, 2 x 2\n"
    "  W                     wireframe\n"
    "  T                     texture / shading on or off (attributes as colour)\n"
    "  O                     rotate the vertex order by one\n"
    "  A                     rotate the vertex order every second (on in the rotating scene)\n"
    "  R                     reset the view\n"
    "  S                     save a screenshot (quadgl-demo-NNN.png)\n"
    "  H                     print this help to stdout\n"
    "  Esc, Q                quit\n"
    "Mouse: drag with the left button to orbit, scroll to zoom.\n"
    "On screen: each panel's method, its frame time, and its error against the software\n"
    "reference (RMS and 99th percentile in 8-bit levels).\n";

const char *demo_options_default_scene_dir(void)
{
    return DEMO_SCENE_DIR;
}

void demo_options_help(FILE *f)
{
    fputs(usage_text, f);
    fputs(options_text, f);
}

static int bad(const char *fmt, const char *what)
{
    fprintf(stderr, "quadgl-demo: ");
    fprintf(stderr, fmt, what);
    fprintf(stderr, "\n%sTry 'quadgl-demo --help'.\n", usage_text);
    return -1;
}

static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (!*s || *end || v < lo || v > hi)
        return -1;
    *out = (int)v;
    return 0;
}

static int parse_methods(const char *list, demo_options *o)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    o->nmethods = 0;
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int m = demo_method_parse(t);
        if (m < 0)
            return bad("unknown method '%s' (native, mvc, auto, subdiv, reference)", t);
        if (o->nmethods == DEMO_NMETHODS)
            return bad("too many methods in '%s'", list);
        o->methods[o->nmethods++] = m;
    }
    return o->nmethods ? 0 : bad("empty method list '%s'", list);
}

static int parse_size(const char *s, demo_options *o)
{
    char w[32], h[32];
    const char *x = strchr(s, 'x');
    if (!x || x - s >= (long)sizeof w || strlen(x + 1) >= sizeof h)
        return bad("bad size '%s' (expected WxH, e.g. 800x600)", s);
    snprintf(w, sizeof w, "%.*s", (int)(x - s), s);
    snprintf(h, sizeof h, "%s", x + 1);
    if (parse_int(w, 16, 8192, &o->width) || parse_int(h, 16, 8192, &o->height))
        return bad("bad size '%s' (each side 16..8192 pixels)", s);
    return 0;
}

static int parse_view(const char *s, demo_options *o)
{
    static const char *const names[] = {"single", "split", "quad"};
    for (int i = 0; i < 3; i++)
        if (strcmp(s, names[i]) == 0) {
            o->layout = (demo_layout)i;
            return 0;
        }
    return bad("unknown view '%s' (single, split or quad)", s);
}

/* An option that takes a value: the value, or NULL after reporting it missing. */
static const char *value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        bad("option '%s' needs a value", argv[*i]);
        return NULL;
    }
    return argv[++*i];
}

static int parse_valued(const char *opt, const char *v, demo_options *o)
{
    if (!strcmp(opt, "--out"))
        o->out_dir = v;
    else if (!strcmp(opt, "--scenes"))
        o->scene_dir = v;
    else if (!strcmp(opt, "--scene"))
        o->scene = v;
    else if (!strcmp(opt, "--method"))
        return parse_methods(v, o);
    else if (!strcmp(opt, "--view"))
        return parse_view(v, o);
    else if (!strcmp(opt, "--size"))
        return parse_size(v, o);
    else if (!strcmp(opt, "--screenshot"))
        o->screenshot = v;
    else if (!strcmp(opt, "--frames"))
        return parse_int(v, 1, 1000000000, &o->frames) ? bad("bad frame count '%s'", v) : 0;
    else if (!strcmp(opt, "--order"))
        return parse_int(v, 0, 3, &o->order) ? bad("bad vertex order '%s' (0..3)", v) : 0;
    else
        return 1;
    return 0;
}

static int parse_flag(const char *opt, demo_options *o)
{
    if (!strcmp(opt, "-h") || !strcmp(opt, "--help"))
        o->help = 1;
    else if (!strcmp(opt, "--list"))
        o->list = 1;
    else if (!strcmp(opt, "--headless"))
        o->headless = 1;
    else if (!strcmp(opt, "--wireframe"))
        o->wireframe = 1;
    else if (!strcmp(opt, "--no-shading"))
        o->shading = 0;
    else if (!strcmp(opt, "--quiet"))
        o->quiet = 1;
    else if (!strcmp(opt, "--no-text"))
        o->no_text = 1;
    else
        return 1;
    return 0;
}

static int is_valued(const char *opt)
{
    static const char *const names[] = {"--out",  "--scenes", "--scene",      "--method", "--view",
                                        "--size", "--frames", "--screenshot", "--order"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (!strcmp(opt, names[i]))
            return 1;
    return 0;
}

int demo_options_parse(int argc, char **argv, demo_options *o)
{
    memset(o, 0, sizeof *o);
    o->shading = 1;
    o->scene_dir = DEMO_SCENE_DIR;
    o->layout = DEMO_VIEW_SPLIT;
    for (int i = 1; i < argc; i++) {
        const char *opt = argv[i];
        if (is_valued(opt)) {
            const char *v = value(argc, argv, &i);
            if (!v || parse_valued(opt, v, o))
                return -1;
        } else if (parse_flag(opt, o)) {
            return bad(opt[0] == '-' ? "unknown option '%s'" : "unexpected argument '%s'", opt);
        }
    }
    if (o->help || o->list)
        return 0;
    if (o->headless && !o->out_dir)
        return bad("%s needs --out DIR", "--headless");
    if (!o->headless && o->out_dir)
        return bad("%s is for --headless runs", "--out");
    return 0;
}
