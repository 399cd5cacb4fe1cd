/* demo_options.h: quadgl-demo's command line, parsed the same way by the window and the
 * headless program (the window program hands --headless runs to its headless sibling with the
 * arguments unchanged). */
#ifndef DEMO_OPTIONS_H
#define DEMO_OPTIONS_H

#include <stdio.h>

#include "demo_app.h"

typedef enum { DEMO_VIEW_SINGLE = 0, DEMO_VIEW_SPLIT, DEMO_VIEW_QUAD } demo_layout;

typedef struct demo_options {
    int help, list, headless;
    const char *out_dir;      /* --out */
    const char *scene_dir;    /* --scenes, default the source tree's scene files */
    const char *scene;        /* --scene: first scene shown (window) or the only one (headless) */
    int methods[DEMO_NMETHODS]; /* --method list, in order */
    int nmethods;             /* 0: the default set */
    demo_layout layout;       /* --view */
    int width, height;        /* --size; 0: default */
    int frames;               /* --frames: quit after this many frames (0: run until closed) */
    const char *screenshot;   /* --screenshot: front buffer after the last frame, as PNG */
    int order;                /* --order */
    int wireframe;            /* --wireframe */
    int shading;              /* --no-shading clears it */
    int quiet;                /* --quiet: no table on stdout */
    int no_text;              /* --no-text: window without the on-screen text */
} demo_options;

/* Parse argv. Returns 0, or -1 after printing "quadgl-demo: <why>" and the usage to stderr. */
int demo_options_parse(int argc, char **argv, demo_options *o);
/* The full help (options and keys) to f. */
void demo_options_help(FILE *f);
/* The default scene directory compiled in (the source tree's scene files). */
const char *demo_options_default_scene_dir(void);

#endif
