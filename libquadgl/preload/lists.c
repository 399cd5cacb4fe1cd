/* lists.c: display lists (glNewList ... glEndList, glCallList(s)), with their geometry kept by us.
 *
 * While a list is compiled, its calls are cut into items. Geometry (every glBegin/glEnd
 * primitive of any mode, quad draws from arrays, and the attribute calls between primitives)
 * collects in a geometry item: one mesh of the GL layer (gl/mesh.c), its vertices in one array
 * per attribute, a table of primitives, the facts of its quads worked out once. Everything
 * else (state changes, other draws, ...) goes to the driver, which compiles it into a segment:
 * a private driver list (a name far above the ones programs use, checked free), or list n
 * itself for the calls before the first geometry; with it we keep which state groups its
 * calls change (track.c), to mark them when the segment runs. glCallList(s) while compiling
 * becomes a call item, resolved when the list runs, as GL resolves nested lists. So our object
 * for list n reads: segment, geometry, segment, call m, ... and glCallList(n) runs it in order:
 * the driver runs each segment, the GL layer draws each mesh in the state the segments left
 * (from a buffer object of its own after the first time: nothing is uploaded again; runs of
 * primitives the driver draws as they are become one multi-draw each, as the driver's own list
 * would merge them), and only the quads that need smoothing are planned and drawn by us. The
 * driver never holds the geometry, so a list costs its memory once, and a program with
 * thousands of small lists does not get thousands of driver lists more. Vertices that take the
 * current value of an attribute (given in the list only later) are filled when the list runs;
 * after a geometry item the current attributes are the last ones it gave, as GL leaves them.
 * Primitives with generic attributes, or that the capture cannot represent, stay primitives
 * of their own, replayed to the driver. GL lets a list begin a primitive and another end it,
 * and a list be called inside glBegin/glEnd: a segment remembers whether its calls leave the
 * driver inside a glBegin or outside, and a list run inside the driver's glBegin draws none of
 * its own primitives there but raises GL_INVALID_OPERATION, as the driver's lists do. (Under
 * GL_COMPILE_AND_EXECUTE such a primitive is compiled only, and run when it ends: the driver
 * cannot begin or end a segment inside its glBegin.) Objects live in the share group of the
 * contexts (a sorted array by name under a mutex) and are reference counted while they run. */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

#define PL_MAX_NESTING 64         /* GL_MAX_LIST_NESTING's minimum */
#define PL_FIRST_SUBLIST 0x40000000u

enum { PL_ITEM_SEGMENT, PL_ITEM_GEOMETRY, PL_ITEM_PRIM, PL_ITEM_CALL, PL_ITEM_CALLS };

/* A geometry item: the mesh, and what it takes from and gives to the current attributes. */
typedef struct pl_geom {
    qgl__mesh m;
    float cur[QGL__NATTR][4]; /* the last values given, left current after the item */
    unsigned char cur_edge;
    unsigned set;             /* attributes (QGL__A_EDGE too) the item gives a value */
    uint32_t lead[QGL__NATTR + 1]; /* vertices before these take the current value at run time */
    float filled[QGL__NATTR][4];   /* the value those vertices hold now */
    unsigned char filled_edge;
    unsigned filled_valid;
    GLuint dl;                /* QUADGL_METHOD=replay: the driver's list of its replay (0: none) */
    int dl_filled;            /* the polygon mode it was compiled for (pl_polygons_filled) */
} pl_geom;

typedef struct pl_item {
    int kind;
    GLuint name;       /* segment: the driver's list; call: the list called */
    unsigned mask;     /* segment: what its calls change (track.c's PL_D_*) */
    int begins;        /* segment: its calls leave the driver inside a glBegin (1), outside (2),
                          or neither begin nor end one (0) */
    pl_geom *geom;     /* PL_ITEM_GEOMETRY */
    pl_prim prim;      /* PL_ITEM_PRIM */
    uint32_t *names;   /* PL_ITEM_CALLS: the names given, the base added when it runs */
    size_t count;
} pl_item;

struct pl_list {
    GLuint name;
    pl_share *share;
    pl_item *items;
    size_t n, cap;
    int refs;
    int open;          /* while compiling: 0 nothing, 1 a segment, 2 the last item's geometry */
    int begins;        /* while compiling: the open segment's begins */
    size_t defer;      /* while compiling under GL_COMPILE_AND_EXECUTE: 1 + the first item of a
                          primitive the driver took over, compiled only and run at its glEnd
                          (the driver cannot begin or end a list inside its glBegin) */
};

struct pl_share {
    pthread_mutex_t lock;
    int refs;
    unsigned images;   /* texture image changes made in any of its contexts (atomic) */
    pl_list **lists;   /* sorted by name */
    size_t n, cap;
    GLuint next_sub;
};

/* ---- share groups ------------------------------------------------------------------------- */

pl_share *pl_share_new(void)
{
    pl_share *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    pthread_mutex_init(&s->lock, NULL);
    s->refs = 1;
    s->next_sub = PL_FIRST_SUBLIST;
    return s;
}

void pl_share_ref(pl_share *s)
{
    __atomic_add_fetch(&s->refs, 1, __ATOMIC_ACQ_REL);
}

/* Texture objects are shared too: an image given in one context (a loader thread's, say)
 * must reach what every other context's GL path keeps of its textures (QGL__D_TEXIMAGE). */
void pl_share_images_changed(pl_share *s)
{
    if (s)
        __atomic_add_fetch(&s->images, 1, __ATOMIC_RELEASE);
}

unsigned pl_share_images(const pl_share *s)
{
    return s ? __atomic_load_n(&s->images, __ATOMIC_ACQUIRE) : 0;
}

/* A mesh's buffer object can be deleted only while a context of its share group is current. */
static void pl_list_free(pl_list *l)
{
    pl_ctx *x = pl_tls_ctx;
    struct qgl__gl *gl = x && x->share == l->share ? pl_gl() : NULL;
    for (size_t i = 0; i < l->n; i++) {
        pl_item *it = &l->items[i];
        if (it->geom) {
            if (gl && it->geom->dl)
                REAL(glDeleteLists)(it->geom->dl, 1);
            qgl__mesh_free(gl, l->share, &it->geom->m);
            free(it->geom);
        }
        pl_prim_free(&it->prim);
        free(it->names);
    }
    free(l->items);
    free(l);
}

static void pl_list_unref(pl_list *l)
{
    if (__atomic_sub_fetch(&l->refs, 1, __ATOMIC_ACQ_REL) == 0)
        pl_list_free(l);
}

void pl_share_unref(pl_share *s)
{
    if (!s || __atomic_sub_fetch(&s->refs, 1, __ATOMIC_ACQ_REL) != 0)
        return;
    for (size_t i = 0; i < s->n; i++)
        pl_list_unref(s->lists[i]);
    free(s->lists);
    pthread_mutex_destroy(&s->lock);
    free(s);
}

/* Index of the first list whose name is >= name. Called with the lock held. */
static size_t pl_share_find(const pl_share *s, GLuint name)
{
    size_t lo = 0, hi = s->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (s->lists[mid]->name < name)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* Our object for list `name`, referenced (pl_list_unref when done), or NULL. */
static pl_list *pl_share_get(pl_share *s, GLuint name)
{
    pl_list *l = NULL;
    size_t i;
    pthread_mutex_lock(&s->lock);
    i = pl_share_find(s, name);
    if (i < s->n && s->lists[i]->name == name) {
        l = s->lists[i];
        l->refs++;
    }
    pthread_mutex_unlock(&s->lock);
    return l;
}

static int pl_share_empty(pl_share *s)
{
    return __atomic_load_n(&s->n, __ATOMIC_RELAXED) == 0;
}

/* The driver's lists of a retired object (its own name belongs to the program). */
static void pl_list_delete_segments(const pl_list *l)
{
    for (size_t i = 0; i < l->n; i++)
        if (l->items[i].kind == PL_ITEM_SEGMENT && l->items[i].name != l->name)
            REAL(glDeleteLists)(l->items[i].name, 1);
}

/* Installs l for its name (NULL l: removes the object for `name`). */
static void pl_share_set(pl_share *s, GLuint name, pl_list *l)
{
    pl_list *old = NULL;
    size_t i;
    pthread_mutex_lock(&s->lock);
    i = pl_share_find(s, name);
    if (i < s->n && s->lists[i]->name == name) {
        old = s->lists[i];
        if (l)
            s->lists[i] = l;
        else
            memmove(s->lists + i, s->lists + i + 1, (--s->n - i) * sizeof *s->lists);
    } else if (l) {
        if (s->n == s->cap) {
            size_t cap = s->cap ? s->cap * 2 : 16;
            pl_list **grown = realloc(s->lists, cap * sizeof *grown);
            if (!grown) {
                pthread_mutex_unlock(&s->lock);
                pl_log(PL_LOG_WARN, "out of memory: display list %u loses its smooth quads", name);
                pl_list_unref(l);
                return;
            }
            s->lists = grown;
            s->cap = cap;
        }
        memmove(s->lists + i + 1, s->lists + i, (s->n - i) * sizeof *s->lists);
        s->lists[i] = l;
        s->n++;
    }
    pthread_mutex_unlock(&s->lock);
    if (old) {
        pl_list_delete_segments(old);
        pl_list_unref(old);
    }
}

/* A list name no program uses: far above glGenLists' and checked free in the driver. */
static GLuint pl_share_new_name(pl_share *s)
{
    GLuint sub;
    pthread_mutex_lock(&s->lock);
    while (REAL(glIsList)(s->next_sub))
        s->next_sub++;
    sub = s->next_sub++;
    pthread_mutex_unlock(&s->lock);
    return sub;
}

/* ---- compiling ------------------------------------------------------------------------------ */

static pl_item *pl_list_push(pl_list *l, int kind, GLuint name)
{
    pl_item *it;
    if (l->n == l->cap) {
        size_t cap = l->cap ? l->cap * 2 : 8;
        pl_item *grown = realloc(l->items, cap * sizeof *grown);
        if (!grown)
            return NULL;
        l->items = grown;
        l->cap = cap;
    }
    it = &l->items[l->n++];
    memset(it, 0, sizeof *it);
    it->kind = kind;
    it->name = name;
    return it;
}

/* Ends whatever item is open: the driver's segment (keeping what its calls changed), or the
 * geometry (its quads' facts worked out). */
static void pl_list_close(pl_ctx *x)
{
    pl_list *l = x->compiling;
    pl_item *it = l->n ? &l->items[l->n - 1] : NULL;
    if (l->open == 1) {
        REAL(glEndList)();
        if (it && it->kind == PL_ITEM_SEGMENT) {
            it->mask |= x->seg_dirty;
            it->begins = l->begins ? l->begins : it->begins;
        }
    } else if (l->open == 2 && it && it->geom && !qgl__mesh_finish(&it->geom->m)) {
        pl_log(PL_LOG_WARN, "out of memory: quads lost from display list %u", l->name);
        it->geom->m.nprim = 0;
    }
    x->seg_dirty = 0;
    l->open = 0;
    l->begins = 0;
}

void pl_list_state(pl_ctx *x)
{
    pl_list *l = x->compiling;
    if (l->open == 1)
        return;
    pl_list_close(x);
    GLuint sub = pl_share_new_name(x->share);
    if (!pl_list_push(l, PL_ITEM_SEGMENT, sub)) {
        pl_log(PL_LOG_WARN, "out of memory while compiling display list %u", l->name);
        return;
    }
    REAL(glNewList)(sub, x->compile_mode);
    l->open = 1;
}

void pl_list_begin_end(pl_ctx *x, int inside)
{
    pl_list_state(x);
    x->compiling->begins = inside ? 1 : 2;
}

static void pl_items_exec(pl_ctx *x, pl_list *l, size_t from, size_t to, int depth);

void pl_list_defer(pl_ctx *x)
{
    pl_list *l = x->compiling;
    pl_list_close(x);
    l->defer = l->n + 1;
    x->compile_mode = GL_COMPILE;
}

/* The deferred primitive's items run now (no segment is open: the driver only runs them). */
void pl_list_end_prim(pl_ctx *x)
{
    pl_list *l = x->compiling;
    size_t from;
    if (!l->defer)
        return;
    pl_list_close(x);
    from = l->defer - 1;
    l->defer = 0;
    x->compile_mode = GL_COMPILE_AND_EXECUTE;
    pl_items_exec(x, l, from, l->n, 1);
    x->cur_known = 0;
}

/* The open geometry item (opened after closing a segment); NULL without memory. */
static pl_geom *pl_list_geometry(pl_ctx *x)
{
    pl_list *l = x->compiling;
    if (l->open == 2)
        return l->items[l->n - 1].geom;
    pl_list_close(x);
    pl_item *it = pl_list_push(l, PL_ITEM_GEOMETRY, 0);
    if (!it)
        return NULL;
    if (!(it->geom = calloc(1, sizeof *it->geom))) {
        l->n--;
        return NULL;
    }
    l->open = 2;
    return it->geom;
}

void pl_list_attrib(pl_ctx *x, int slot, const float v[4])
{
    pl_geom *g = pl_list_geometry(x);
    if (!g)
        return;
    if (slot == QGL__NATTR) {
        g->cur_edge = v[0] != 0;
        g->set |= QGL__A_EDGE;
    } else {
        memcpy(g->cur[slot], v, sizeof g->cur[slot]);
        g->set |= 1u << slot;
    }
}

/* Appends a finished primitive to the open geometry. Its attributes given only from a later
 * vertex take, before it, the value the item last gave, or (none yet) the current value when
 * the list runs; an attribute the item gave before and the primitive does not, that value. */
static int pl_geom_add(pl_geom *g, const pl_prim *p)
{
    qgl__verts *m = &g->m.v;
    size_t base = m->n, n = p->v.n;
    unsigned old = m->mask, mask = old | p->v.mask | (g->set & (QGL__A_ATTRIBS | QGL__A_EDGE));
    if (!qgl__verts_reserve(m, base + n, mask))
        return 0;
    if (n) /* a primitive with no vertex may have no arrays at all */
        memcpy(m->pos + 4 * base, p->v.pos, 16 * n);
    for (int a = 0; a <= QGL__NATTR; a++) {
        unsigned bit = a == QGL__NATTR ? QGL__A_EDGE : 1u << a;
        if (!(mask & bit))
            continue;
        int given = (p->v.mask & bit) != 0;
        size_t from = given ? p->first[a] : n; /* the primitive's own values from here on */
        if (from > n)
            from = n;
        if (!(old & bit))
            g->lead[a] = (uint32_t)(base + ((g->set & bit) ? 0 : from));
        if (g->set & bit)
            pl_verts_fill(m, a, base, base + from, a == QGL__NATTR ? NULL : g->cur[a], g->cur_edge);
        if (!given)
            continue;
        if (a == QGL__NATTR) {
            if (n > from)
                memcpy(m->edge + base + from, p->v.edge + from, n - from);
            g->cur_edge = p->cur_edge;
        } else {
            size_t k = (size_t)qgl__attribs[a].floats;
            if (n > from)
                memcpy(m->attr[a] + k * (base + from), p->v.attr[a] + k * from, k * (n - from) * sizeof(float));
            memcpy(g->cur[a], p->cur[a], sizeof g->cur[a]);
        }
        g->set |= bit;
    }
    m->mask = mask;
    m->n = base + n;
    return qgl__mesh_add_prim(&g->m, p->mode, base, n, p->v.mask & (QGL__A_ATTRIBS | QGL__A_EDGE), p->mat, p->nmat);
}

void pl_list_add_prim(pl_ctx *x, const pl_prim *p)
{
    pl_list *l = x->compiling;
    if (p->lost || p->generic_given) {
        pl_list_close(x);
        pl_item *it = pl_list_push(l, PL_ITEM_PRIM, 0);
        if (!it || pl_prim_copy(&it->prim, p) != 0) {
            if (it)
                l->n--;
            pl_log(PL_LOG_WARN, "out of memory: quads lost from display list %u", l->name);
        } else {
            it->prim.in_list = 1;
        }
        return;
    }
    pl_geom *g = pl_list_geometry(x);
    if (!g || !pl_geom_add(g, p))
        pl_log(PL_LOG_WARN, "out of memory: primitives lost from display list %u", l->name);
}

/* A list command inside a captured primitive: GL_INVALID_OPERATION now, never compiled (list
 * commands run at once, even while a list is compiled). */
static void pl_list_error_now(pl_ctx *x)
{
    if (x->compiling)
        pl_list_close(x);
    REAL(glEnd)(); /* the driver saw no glBegin: the error, nothing else */
}

PL_EXPORT void glNewList(GLuint list, GLenum mode)
{
    pl_ctx *x = pl_tls_ctx;
    pl_list *l;
    if (!x && pl_cfg.capture)
        x = pl_current();
    if (x && x->capturing) {
        pl_list_error_now(x);
        return;
    }
    if (x)
        pl_batch_flush(x);
    if (x && x->compiling)
        pl_list_state(x); /* the driver's list is open: its own error */
    if (!x || !pl_cfg.capture || x->compiling || x->native_begin || list == 0 ||
        (mode != GL_COMPILE && mode != GL_COMPILE_AND_EXECUTE) || !(l = calloc(1, sizeof *l))) {
        REAL(glNewList)(list, mode);
        return;
    }
    l->name = list;
    l->share = x->share;
    l->refs = 1;
    x->compiling = l;
    x->compile_mode = mode;
    x->seg_dirty = 0;
    pl_update_slow(x);
    REAL(glNewList)(list, mode);
    pl_list_push(l, PL_ITEM_SEGMENT, list);
    l->open = 1;
}

PL_EXPORT void glEndList(void)
{
    pl_ctx *x = pl_tls_ctx;
    pl_list *l;
    if (x && x->capturing && (!x->compiling || x->compile_mode != GL_COMPILE)) {
        pl_list_error_now(x);
        return;
    }
    if (!x || !x->compiling) {
        REAL(glEndList)();
        return;
    }
    if (x->capturing) /* GL_COMPILE: the list ends inside its primitive */
        pl_cap_to_driver(x);
    l = x->compiling;
    pl_list_end_prim(x);
    pl_list_close(x);
    x->compiling = NULL;
    pl_update_slow(x);
    if (l->n == 1 && l->items[0].kind == PL_ITEM_SEGMENT && !l->items[0].mask && !l->items[0].begins) {
        /* Nothing recorded and nothing tracked changed: the driver's list is the whole list. */
        pl_share_set(x->share, l->name, NULL);
        pl_list_unref(l);
        return;
    }
    pl_share_set(x->share, l->name, l);
}

PL_EXPORT void glListBase(GLuint base)
{
    pl_ctx *x = pl_tls_ctx;
    if (PL_UNLIKELY(pl_touch(PL_D_LIST_BASE)))
        return;
    REAL(glListBase)(base);
    if (x && !x->native_begin && (!x->compiling || x->compile_mode == GL_COMPILE_AND_EXECUTE)) {
        x->list_base = (GLint)base;
        x->list_base_known = 1;
    }
}

PL_EXPORT void glDeleteLists(GLuint list, GLsizei range)
{
    pl_ctx *x = pl_tls_ctx;
    if (PL_UNLIKELY(pl_touch(0)))
        return;
    REAL(glDeleteLists)(list, range);
    if (!x || range <= 0 || pl_share_empty(x->share))
        return;
    for (;;) {
        GLuint name = 0;
        size_t i;
        pthread_mutex_lock(&x->share->lock);
        i = pl_share_find(x->share, list);
        if (i < x->share->n && (uint64_t)x->share->lists[i]->name < (uint64_t)list + (uint64_t)range)
            name = x->share->lists[i]->name;
        pthread_mutex_unlock(&x->share->lock);
        if (!name)
            break;
        pl_share_set(x->share, name, NULL);
    }
}

/* ---- executing ------------------------------------------------------------------------------ */

/* The driver draws the mesh's primitives itself, as the calls that made them; GL_QUADS, when
 * the polygons are filled, as the triangles its display lists split them into (0-1-3, 1-2-3),
 * not its immediate mode's, each vertex with its own materials (qgl__matrun). */
/* The attributes a primitive does not give (not in given) from vertex i's values, outside
 * glBegin/glEnd, as the program's list sets them between primitives; those before the
 * geometry's own first value stay the state's. */
static void pl_geom_state(const pl_geom *g, unsigned given, size_t i)
{
    struct qgl__gl *gl = pl_gl();
    const qgl__verts *v = &g->m.v;
    unsigned state = v->mask & ~given;
    for (int a = 0; a < QGL__NATTR; a++)
        if ((state & (1u << a)) && i >= g->lead[a])
            qgl__set_current(gl, a, v->attr[a] + (size_t)qgl__attribs[a].floats * i);
    if ((state & QGL__A_EDGE) && i >= g->lead[QGL__NATTR])
        gl->EdgeFlag(v->edge[i]);
}

static int pl_geom_state_differs(const pl_geom *g, unsigned given, size_t i, size_t j)
{
    const qgl__verts *v = &g->m.v;
    unsigned state = v->mask & ~given;
    for (int a = 0; a < QGL__NATTR; a++) {
        size_t k = (size_t)qgl__attribs[a].floats;
        if ((state & (1u << a)) && memcmp(v->attr[a] + k * i, v->attr[a] + k * j, k * sizeof(float)) != 0)
            return 1;
    }
    return (state & QGL__A_EDGE) && v->edge[i] != v->edge[j];
}

static void pl_geom_replay(const pl_geom *g, int count)
{
    static const int split[6] = {0, 1, 3, 1, 2, 3};
    struct qgl__gl *gl = pl_gl();
    const qgl__mesh *m = &g->m;
    const qgl__verts *v = &m->v;
    int filled = pl_polygons_filled();
    for (size_t k = 0; k < m->nprim; k++) {
        const qgl__mesh_prim *p = &m->prim[k];
        int tris = p->mode == GL_QUADS && filled;
        size_t n = tris ? 6 * (p->count / 4) : p->count;
        unsigned given = p->given & v->mask;
        qgl__matrun r;
        qgl__matrun_start(gl, &r, m->chg + p->chg0, p->nchg);
        pl_geom_state(g, given, p->first);
        gl->Begin(tris ? GL_TRIANGLES : p->mode);
        for (size_t j = 0; j < n; j++) {
            size_t i = p->first + (tris ? 4 * (j / 6) + (size_t)split[j % 6] : j);
            /* GL_QUADS primitives in a row are one here (qgl__mesh_add_prim): the values set
             * between them change at a quad's first vertex */
            if (p->mode == GL_QUADS && j > 0 && (tris ? j % 6 == 0 : j % 4 == 0) &&
                pl_geom_state_differs(g, given, i, i - 4)) {
                gl->End();
                pl_geom_state(g, given, i);
                gl->Begin(tris ? GL_TRIANGLES : p->mode);
            }
            if (tris && j % 6 == 0)
                qgl__matrun_quad(&r, i);
            if (tris)
                qgl__matrun_emit(gl, &r, split[j % 6]);
            else
                qgl__matrun_to(gl, &r, i);
            for (int a = 0; a < QGL__NATTR; a++)
                if (given & (1u << a))
                    qgl__set_current(gl, a, v->attr[a] + (size_t)qgl__attribs[a].floats * i);
            if (given & QGL__A_EDGE)
                gl->EdgeFlag(v->edge[i]);
            gl->Vertex4fv(v->pos + 4 * i);
        }
        gl->End();
        qgl__matrun_to(gl, &r, SIZE_MAX);
        if (count && (p->mode == GL_QUADS || p->mode == GL_QUAD_STRIP))
            pl_count_passthrough(qgl__nquads(p->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP, p->count));
    }
}

/* The leading vertices that take the current value get it (the buffer is refilled if it moved). */
static void pl_geom_lead(pl_ctx *x, pl_geom *g)
{
    int changed = 0;
    for (int a = 0; a <= QGL__NATTR; a++) {
        if (!g->lead[a])
            continue;
        unsigned bit = a == QGL__NATTR ? QGL__A_EDGE : 1u << a;
        float now[4] = {0, 0, 0, 0};
        unsigned char edge = 0;
        if (a == QGL__NATTR)
            edge = pl_current_edge(x);
        else
            pl_current_value(x, a, now);
        if ((g->filled_valid & bit) &&
            (a == QGL__NATTR ? edge == g->filled_edge : !memcmp(now, g->filled[a], sizeof now)))
            continue;
        pl_verts_fill(&g->m.v, a, 0, g->lead[a], now, edge);
        if (a == QGL__NATTR)
            g->filled_edge = edge;
        else
            memcpy(g->filled[a], now, sizeof now);
        g->filled_valid |= bit;
        changed = 1;
    }
    if (changed)
        qgl__mesh_changed(&g->m);
}

/* Whether the replay of g may be compiled once into a driver list: what it takes from the state
 * when it runs (current values before an attribute is first given, materials before the first
 * change of a primitive) it must take from the state, not from its vertices. */
static int pl_geom_compilable(const pl_geom *g)
{
    const qgl__mesh *m = &g->m;
    for (int a = 0; a <= QGL__NATTR; a++) {
        int at_start = !g->lead[a];
        for (size_t k = 0; k < m->nprim && !at_start; k++)
            at_start = m->prim[k].first == g->lead[a];
        if (!at_start)
            return 0;
    }
    for (size_t k = 0; k < m->nprim; k++)
        if (!qgl__matrun_leading(m->chg + m->prim[k].chg0, m->prim[k].nchg, m->prim[k].first))
            return 0;
    return 1;
}

/* QUADGL_METHOD=replay: the driver draws g from a list of its own holding the replay, so that
 * its vertices reach the driver as its lists keep them (the attributes each primitive gave, a
 * vertex format per run of primitives), not as its immediate mode's, which keeps attributes
 * given earlier in its vertex format and lights them as inputs rather than as state. */
static void pl_geom_call(pl_ctx *x, pl_geom *g)
{
    int filled = pl_polygons_filled();
    if (g->dl && g->dl_filled != filled) {
        REAL(glDeleteLists)(g->dl, 1);
        g->dl = 0;
    }
    if (!g->dl) {
        g->dl = pl_share_new_name(x->share);
        g->dl_filled = filled;
        REAL(glNewList)(g->dl, GL_COMPILE);
        pl_geom_replay(g, 0);
        REAL(glEndList)();
    }
    REAL(glCallList)(g->dl);
    for (size_t k = 0; k < g->m.nprim; k++) {
        const qgl__mesh_prim *p = &g->m.prim[k];
        if (p->mode == GL_QUADS || p->mode == GL_QUAD_STRIP)
            pl_count_passthrough(qgl__nquads(p->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP, p->count));
    }
}

static void pl_geom_exec(pl_ctx *x, pl_geom *g)
{
    struct qgl__gl *gl;
    qgl_context *qgl;
    if (g->m.nprim && x->native_begin) {
        pl_invalid_operation();
        return;
    }
    if (g->m.nprim) {
        qgl = pl_cfg.replay ? NULL : pl_ctx_qgl(x);
        pl_geom_lead(x, g);
        if (pl_cfg.replay && !x->compiling && pl_geom_compilable(g))
            pl_geom_call(x, g);
        else if (!qgl || qgl__mesh_draw(qgl, &g->m, x->share) < 0)
            pl_geom_replay(g, 1);
    }
    gl = pl_gl();
    for (int a = 0; a < QGL__NATTR; a++)
        if (g->set & (1u << a)) {
            qgl__set_current(gl, a, g->cur[a]);
            pl_note_current(x, a, g->cur[a]);
        }
    if (g->set & QGL__A_EDGE) {
        gl->EdgeFlag(g->cur_edge);
        pl_hook_edgeflag(x, g->cur_edge);
    }
}

static void pl_list_exec(pl_ctx *x, GLuint name, int depth);

/* The list base: glListBase's value, or asked of the driver (never inside its glBegin). */
static GLint pl_list_base(pl_ctx *x)
{
    if (!x->list_base_known && !x->native_begin) {
        x->list_base = 0;
        REAL(glGetIntegerv)(GL_LIST_BASE, &x->list_base);
        x->list_base_known = 1;
    }
    return x->list_base;
}

static void pl_exec_calls(pl_ctx *x, const uint32_t *names, size_t count, int depth)
{
    GLint base = pl_list_base(x);
    for (size_t k = 0; k < count; k++)
        pl_list_exec(x, (GLuint)base + names[k], depth);
}

/* Items [from, to) of l, in order. */
static void pl_items_exec(pl_ctx *x, pl_list *l, size_t from, size_t to, int depth)
{
    for (size_t i = from; i < to; i++) {
        pl_item *it = &l->items[i];
        switch (it->kind) {
        case PL_ITEM_SEGMENT:
            REAL(glCallList)(it->name);
            pl_mark(x, it->mask);
            if (it->begins)
                x->native_begin = it->begins == 1;
            break;
        case PL_ITEM_GEOMETRY: pl_geom_exec(x, it->geom); break;
        case PL_ITEM_PRIM:
            if (x->native_begin)
                pl_invalid_operation();
            else
                pl_draw_prim(x, &it->prim);
            break;
        case PL_ITEM_CALL: pl_list_exec(x, it->name, depth + 1); break;
        default: pl_exec_calls(x, it->names, it->count, depth + 1); break;
        }
    }
}

static void pl_list_exec(pl_ctx *x, GLuint name, int depth)
{
    pl_list *l;
    if (depth >= PL_MAX_NESTING)
        return;
    l = pl_share_get(x->share, name);
    if (!l) {
        REAL(glCallList)(name);
        return;
    }
    pl_items_exec(x, l, 0, l->n, depth);
    pl_list_unref(l);
}

/* glCallLists' names as integers; -1 for a type GL does not accept. */
static int pl_decode_names(GLsizei n, GLenum type, const void *lists, uint32_t *out)
{
    const unsigned char *b = lists;
    for (GLsizei i = 0; i < n; i++) {
        switch (type) {
        case GL_BYTE: out[i] = (uint32_t)((const GLbyte *)lists)[i]; break;
        case GL_UNSIGNED_BYTE: out[i] = b[i]; break;
        case GL_SHORT: out[i] = (uint32_t)((const GLshort *)lists)[i]; break;
        case GL_UNSIGNED_SHORT: out[i] = ((const GLushort *)lists)[i]; break;
        case GL_INT: out[i] = (uint32_t)((const GLint *)lists)[i]; break;
        case GL_UNSIGNED_INT: out[i] = ((const GLuint *)lists)[i]; break;
        case GL_FLOAT: out[i] = (uint32_t)((const GLfloat *)lists)[i]; break;
        case GL_2_BYTES: out[i] = (uint32_t)b[2 * i] << 8 | b[2 * i + 1]; break;
        case GL_3_BYTES: out[i] = (uint32_t)b[3 * i] << 16 | (uint32_t)b[3 * i + 1] << 8 | b[3 * i + 2]; break;
        case GL_4_BYTES:
            out[i] = (uint32_t)b[4 * i] << 24 | (uint32_t)b[4 * i + 1] << 16 | (uint32_t)b[4 * i + 2] << 8 | b[4 * i + 3];
            break;
        default: return -1;
        }
    }
    return 0;
}

/* While compiling: the call is recorded (and run too under GL_COMPILE_AND_EXECUTE). */
static void pl_compile_call(pl_ctx *x, int kind, GLuint name, uint32_t *names, size_t count)
{
    pl_item *it;
    pl_list_close(x);
    it = pl_list_push(x->compiling, kind, name);
    if (it) {
        it->names = names;
        it->count = count;
    } else {
        free(names);
        pl_log(PL_LOG_WARN, "out of memory while compiling display list %u", x->compiling->name);
    }
    if (x->compile_mode == GL_COMPILE_AND_EXECUTE) {
        if (kind == PL_ITEM_CALL)
            pl_list_exec(x, name, 1);
        else if (it)
            pl_exec_calls(x, names, count, 1);
    }
}

PL_EXPORT void glCallList(GLuint list)
{
    pl_ctx *x = pl_tls_ctx;
    if (x && !x->capturing)
        pl_batch_flush(x);
    if (!x || !pl_cfg.capture) {
        REAL(glCallList)(list);
        return;
    }
    if (x->capturing)
        pl_cap_to_driver(x);
    if (x->compiling) {
        pl_compile_call(x, PL_ITEM_CALL, list, NULL, 0);
        return;
    }
    if (pl_share_empty(x->share)) {
        REAL(glCallList)(list);
        return;
    }
    PL_TIMED(pl_list_exec(x, list, 0));
}

/* Whether any of the names (plus the current base) is one of ours. */
static int pl_any_ours(pl_ctx *x, const uint32_t *names, GLsizei n)
{
    GLint base = pl_list_base(x);
    for (GLsizei i = 0; i < n; i++) {
        pl_list *l = pl_share_get(x->share, (GLuint)base + names[i]);
        if (l) {
            pl_list_unref(l);
            return 1;
        }
    }
    return 0;
}

PL_EXPORT void glCallLists(GLsizei n, GLenum type, const void *lists)
{
    pl_ctx *x = pl_tls_ctx;
    uint32_t *names;
    if (x && !x->capturing)
        pl_batch_flush(x);
    if (x && x->capturing && pl_cfg.capture && n > 0 && lists)
        pl_cap_to_driver(x);
    if (!x || !pl_cfg.capture || n <= 0 || !lists || (!x->compiling && pl_share_empty(x->share)) ||
        !(names = malloc((size_t)n * sizeof *names))) {
        REAL(glCallLists)(n, type, lists);
        return;
    }
    if (pl_decode_names(n, type, lists, names) != 0) {
        free(names);
        REAL(glCallLists)(n, type, lists); /* the driver's GL_INVALID_ENUM */
        return;
    }
    if (x->compiling) {
        pl_compile_call(x, PL_ITEM_CALLS, 0, names, (size_t)n);
        return;
    }
    if (pl_any_ours(x, names, n))
        PL_TIMED(pl_exec_calls(x, names, (size_t)n, 0));
    else
        REAL(glCallLists)(n, type, lists);
    free(names);
}
