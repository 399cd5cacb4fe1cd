/* lists.c: display lists that hold quads (glNewList ... glEndList, glCallList(s)).
 *
 * The driver keeps compiling everything it always compiled; we only cut its list into
 * segments around what we must see at execution time. glNewList(n) starts the driver's
 * list n as the first segment. A captured quad primitive, an array draw of quads or a
 * glCallList(s) ends the current segment, is recorded in our own list object for n, and a
 * fresh driver list (a private name far above the ones programs use) takes the calls that
 * follow. So our object for n reads: segment, quads, segment, call m, segment, ... and
 * glCallList(n) replays it in order: the driver runs each segment (state changes, other
 * primitives, everything), we draw the quads in the state those segments left, and nested
 * lists are looked up when they run, as GL resolves them. A list in which we recorded
 * nothing gets no object: the driver's list n is complete and glCallList(n) goes straight
 * to it. Objects live in the share group of the contexts (a sorted array by name under a
 * mutex) and are reference counted while they run. */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

#define PL_MAX_NESTING 64         /* GL_MAX_LIST_NESTING's minimum */
#define PL_FIRST_SUBLIST 0x40000000u

enum { PL_ITEM_SEGMENT, PL_ITEM_PRIM, PL_ITEM_CALL, PL_ITEM_CALLS };

typedef struct pl_item {
    int kind;
    GLuint name;       /* segment: the driver's list; call: the list called */
    unsigned mask;     /* segment: what its calls change (track.c's PL_D_*) */
    pl_prim prim;      /* PL_ITEM_PRIM */
    uint32_t *names;   /* PL_ITEM_CALLS: the names given, the base added when it runs */
    size_t count;
} pl_item;

struct pl_list {
    GLuint name;
    pl_item *items;
    size_t n, cap;
    int refs;
};

struct pl_share {
    pthread_mutex_t lock;
    int refs;
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

static void pl_list_free(pl_list *l)
{
    for (size_t i = 0; i < l->n; i++) {
        pl_prim_free(&l->items[i].prim);
        free(l->items[i].names);
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
    for (size_t i = 0; i < l->n; i++) {
        if (l->items[i].kind == PL_ITEM_SEGMENT && l->items[i].name != l->name)
            REAL(glDeleteLists)(l->items[i].name, 1);
        if (l->items[i].kind == PL_ITEM_PRIM && l->items[i].prim.native_list)
            REAL(glDeleteLists)(l->items[i].prim.native_list, 1);
    }
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

/* The open segment is the last segment item: it keeps what its calls changed. */
static void pl_segment_mask(pl_ctx *x)
{
    pl_list *l = x->compiling;
    for (size_t i = l->n; i-- > 0;)
        if (l->items[i].kind == PL_ITEM_SEGMENT) {
            l->items[i].mask |= x->seg_dirty;
            break;
        }
    x->seg_dirty = 0;
}

void pl_list_segment_close(pl_ctx *x)
{
    pl_segment_mask(x);
    REAL(glEndList)();
}

void pl_list_segment_open(pl_ctx *x)
{
    GLuint sub = pl_share_new_name(x->share);
    REAL(glNewList)(sub, x->compile_mode);
    if (!pl_list_push(x->compiling, PL_ITEM_SEGMENT, sub))
        pl_log(PL_LOG_WARN, "out of memory while compiling display list %u", x->compiling->name);
}

void pl_list_record_prim(pl_ctx *x, const pl_prim *p)
{
    pl_item *it = pl_list_push(x->compiling, PL_ITEM_PRIM, 0);
    if (!it || pl_prim_copy(&it->prim, p) != 0) {
        if (it)
            x->compiling->n--;
        pl_log(PL_LOG_WARN, "out of memory: quads lost from display list %u", x->compiling->name);
    }
}

void pl_list_native_begin(pl_ctx *x)
{
    pl_item *it = x->compiling->n ? &x->compiling->items[x->compiling->n - 1] : NULL;
    if (!it || it->kind != PL_ITEM_PRIM)
        return;
    it->prim.native_list = pl_share_new_name(x->share);
    REAL(glNewList)(it->prim.native_list, GL_COMPILE);
}

void pl_list_native_end(pl_ctx *x)
{
    pl_item *it = x->compiling->n ? &x->compiling->items[x->compiling->n - 1] : NULL;
    if (it && it->kind == PL_ITEM_PRIM && it->prim.native_list)
        REAL(glEndList)();
}

PL_EXPORT void glNewList(GLuint list, GLenum mode)
{
    pl_ctx *x = pl_tls_ctx;
    pl_list *l;
    if (!x && pl_cfg.capture)
        x = pl_current();
    if (x && x->capturing) {
        pl_invalid_operation();
        return;
    }
    if (!x || !pl_cfg.capture || x->compiling || x->native_begin || list == 0 ||
        (mode != GL_COMPILE && mode != GL_COMPILE_AND_EXECUTE) || !(l = calloc(1, sizeof *l))) {
        REAL(glNewList)(list, mode);
        return;
    }
    l->name = list;
    l->refs = 1;
    x->compiling = l;
    x->compile_mode = mode;
    x->seg_dirty = 0;
    pl_update_slow(x);
    REAL(glNewList)(list, mode);
    pl_list_push(l, PL_ITEM_SEGMENT, list);
}

PL_EXPORT void glEndList(void)
{
    pl_ctx *x = pl_tls_ctx;
    pl_list *l;
    if (x && x->capturing) {
        pl_invalid_operation();
        return;
    }
    if (!x || !x->compiling) {
        REAL(glEndList)();
        return;
    }
    pl_segment_mask(x);
    REAL(glEndList)();
    l = x->compiling;
    x->compiling = NULL;
    pl_update_slow(x);
    if (l->n <= 1 && !l->items[0].mask) {
        /* Nothing recorded and nothing tracked changed: the driver's list is the whole list. */
        pl_share_set(x->share, l->name, NULL);
        pl_list_unref(l);
        return;
    }
    pl_share_set(x->share, l->name, l);
}

PL_EXPORT void glDeleteLists(GLuint list, GLsizei range)
{
    pl_ctx *x = pl_tls_ctx;
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

static void pl_list_exec(pl_ctx *x, GLuint name, int depth);

static void pl_exec_calls(pl_ctx *x, const uint32_t *names, size_t count, int depth)
{
    GLint base = 0;
    REAL(glGetIntegerv)(GL_LIST_BASE, &base);
    for (size_t k = 0; k < count; k++)
        pl_list_exec(x, (GLuint)base + names[k], depth);
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
    for (size_t i = 0; i < l->n; i++) {
        pl_item *it = &l->items[i];
        switch (it->kind) {
        case PL_ITEM_SEGMENT:
            REAL(glCallList)(it->name);
            x->dirty |= it->mask & PL_D_STATE;
            if (it->mask & PL_D_CURRENT)
                x->cur_known = 0;
            break;
        case PL_ITEM_PRIM: pl_draw_listed(x, &it->prim); break;
        case PL_ITEM_CALL: pl_list_exec(x, it->name, depth + 1); break;
        default: pl_exec_calls(x, it->names, it->count, depth + 1); break;
        }
    }
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
    pl_list_segment_close(x);
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
    pl_list_segment_open(x);
}

PL_EXPORT void glCallList(GLuint list)
{
    pl_ctx *x = pl_tls_ctx;
    if (!x || x->capturing || x->native_begin || !pl_cfg.capture) {
        REAL(glCallList)(list);
        return;
    }
    if (x->compiling) {
        pl_compile_call(x, PL_ITEM_CALL, list, NULL, 0);
        return;
    }
    if (pl_share_empty(x->share)) {
        REAL(glCallList)(list);
        return;
    }
    pl_list_exec(x, list, 0);
}

/* Whether any of the names (plus the current base) is one of ours. */
static int pl_any_ours(pl_ctx *x, const uint32_t *names, GLsizei n)
{
    GLint base = 0;
    REAL(glGetIntegerv)(GL_LIST_BASE, &base);
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
    if (!x || x->capturing || x->native_begin || !pl_cfg.capture || n <= 0 || !lists ||
        (!x->compiling && pl_share_empty(x->share)) || !(names = malloc((size_t)n * sizeof *names))) {
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
        pl_exec_calls(x, names, (size_t)n, 0);
    else
        REAL(glCallLists)(n, type, lists);
    free(names);
}
