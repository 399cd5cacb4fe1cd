/* pt.h: harness of the preload tests: legacy GL scenes drawn with and without the library.
 *
 * A test program is an ordinary legacy OSMesa program linked against libOSMesa only; meson
 * runs it with libquadgl-preload.so in LD_PRELOAD. Each scene is drawn twice: in this process
 * (through the library) and in a child, this same program started again without LD_PRELOAD
 * (the native driver), which sends back its pixels and any values the scene records (glGetError
 * results, say). The comparison depends on QUADGL_METHOD: off and replay must give the native
 * pixels exactly; the drawing methods must match the native pixels outside the quads the
 * scene declares, match the mean value reference (qgl_weights per pixel centre) inside
 * them, and, where a scene declares non-affine quads, visibly differ from the native split. */
#ifndef PT_HARNESS_H
#define PT_HARNESS_H

#include <GL/gl.h>
#include <stdint.h>

#define PT_W 64
#define PT_H 64
#define PT_MAX_QUADS 64
#define PT_MAX_VALUES 256

/* Three non-affine quads of the scenes (colour corners that no plane fits: a quad split on the
 * other diagonal, or a corner with another corner's values, shows). */
static const float Q[3][4][2] = {
    {{-0.9f, -0.9f}, {-0.1f, -0.8f}, {-0.2f, -0.1f}, {-0.8f, -0.3f}},
    {{0.1f, -0.9f}, {0.9f, -0.9f}, {0.8f, -0.2f}, {0.2f, -0.1f}},
    {{-0.9f, 0.1f}, {-0.1f, 0.2f}, {-0.2f, 0.9f}, {-0.9f, 0.8f}},
};
static const float C[3][4][4] = {
    {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}},
    {{1, 1, 0, 1}, {0, 1, 1, 1}, {1, 0, 1, 1}, {0.2f, 0.2f, 0.2f, 1}},
    {{0, 0, 0, 1}, {1, 0.5f, 0, 1}, {0, 0, 0, 1}, {0, 0.5f, 1, 1}},
};

typedef struct pt_quad {
    float v[4][2];   /* corners in normalized device coordinates, GL order */
    float c[4][4];   /* colours (RGBA) at the corners */
    int flat;        /* 0, or 1 + the corner whose colour fills the quad (flat shading) */
} pt_quad;

typedef struct pt_run {
    unsigned char pixels[PT_W * PT_H * 4];
    uint32_t values[PT_MAX_VALUES];
    int nvalues;
    pt_quad quads[PT_MAX_QUADS]; /* what the scene drew, for the reference */
    int nquads;
    int checks_reference;   /* the quads above are the whole picture's quads, in plain colour */
    int native_equal;       /* the picture must equal the native one (affine quads, states
                               the driver draws itself) within 2/255 */
    int min_quads;          /* quads the library must have seen (not in off mode) */
    char failure[160];      /* what a scene found wrong in the library's counters */
} pt_run;

typedef struct pt_scene {
    const char *name;
    void (*draw)(pt_run *r);
} pt_scene;

void pt_value(pt_run *r, uint32_t v);
void pt_expect(pt_run *r, const float v[4][2], const float c[4][4], int flat);
/* Runs the scene named argv[1] (and, with argv[1] == "--native", the child's side). Returns
 * the exit code: 0 pass, 1 fail, 77 skip. */
int pt_main(int argc, char **argv, const pt_scene *scenes, int nscenes);

/* The preload library's counters (quads, mvc, split, subdiv, passthrough, draws, list
 * uploads, frames) and its method; 0, or -1 when the library is not loaded (the native run,
 * QUADGL_METHOD=off or replay: nothing to count). */
enum { PT_QUADS, PT_MVC, PT_SPLIT, PT_SUBDIV, PT_PASS, PT_DRAWS, PT_UPLOADS, PT_FRAMES, PT_NCOUNTERS };
int pt_counters(uint64_t out[PT_NCOUNTERS]);

/* Whether this run goes through libquadgl-preload.so (not the native child). */
int pt_preloaded(void);

/* For scenes: an orthographic identity view, cleared to opaque black. */
void pt_begin_frame(void);

#endif
