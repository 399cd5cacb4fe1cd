/* stream.c: vertex data handed to the driver through one buffer object that is only appended to.
 *
 * A batch's arrays are copied into a buffer the driver keeps mapped (GL 4.4 buffer storage,
 * persistent and coherent), each batch after the previous one; when the buffer is full it is
 * retired with a fence and replaced: by a retired buffer whose fence says the driver has read
 * it (a frame or so later), or by a fresh one. So writing never waits for the driver, no draw
 * in flight sees its data change, and steady drawing reuses a few buffers instead of
 * faulting in new memory.
 * Rewriting one buffer with glBufferSubData instead made llvmpipe finish its whole scene at
 * every batch (the buffer was still in use), several times the cost of the draws themselves.
 * Without buffer storage the same discipline runs on ranges mapped unsynchronized, the buffer
 * orphaned when full. */
#include <string.h>

#include "gl_internal.h"

/* Bytes per buffer: a few batches of a typical frame, small next to a program's memory. */
#define QGL__STREAM_SIZE ((size_t)1 << 20)

/* Deleting a buffer unmaps it; the driver keeps its storage while draws still read it. */
static void stream_release(qgl_context *ctx)
{
    qgl__stream *s = &ctx->stream;
    if (!s->buf)
        return;
    if (!ctx->gl_gone)
        ctx->gl.DeleteBuffers(1, &s->buf);
    s->buf = 0;
    s->map = NULL;
}

static void pool_drop(qgl_context *ctx, int i)
{
    qgl__stream *s = &ctx->stream;
    if (!ctx->gl_gone) {
        ctx->gl.DeleteBuffers(1, &s->pool[i].buf);
        if (s->pool[i].done)
            ctx->gl.DeleteSync(s->pool[i].done);
    }
    memmove(s->pool + i, s->pool + i + 1, (size_t)(--s->npool - i) * sizeof *s->pool);
}

/* The current buffer joins the pool, fenced; the oldest goes when the pool is full. */
static void retire(qgl_context *ctx)
{
    qgl__stream *s = &ctx->stream;
    if (!s->buf)
        return;
    if (!s->persistent || !ctx->gl.FenceSync) {
        stream_release(ctx);
        return;
    }
    if (s->npool == QGL__STREAM_POOL)
        pool_drop(ctx, 0);
    s->pool[s->npool++] = (qgl__stream_buf){s->buf, s->map, s->size, ctx->gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0)};
    s->buf = 0;
    s->map = NULL;
}

/* A retired buffer of at least bytes the driver is done with, made current; 0 if none. */
static int reuse(qgl_context *ctx, size_t bytes)
{
    qgl__stream *s = &ctx->stream;
    for (int i = 0; i < s->npool; i++) {
        qgl__stream_buf *b = &s->pool[i];
        if (b->size < bytes || !b->done)
            continue;
        GLenum r = ctx->gl.ClientWaitSync(b->done, 0, 0);
        if (r != GL_ALREADY_SIGNALED && r != GL_CONDITION_SATISFIED)
            continue;
        ctx->gl.DeleteSync(b->done);
        s->buf = b->buf, s->map = b->map, s->size = b->size;
        memmove(s->pool + i, s->pool + i + 1, (size_t)(--s->npool - i) * sizeof *s->pool);
        ctx->gl.BindBuffer(GL_ARRAY_BUFFER, s->buf);
        s->head = 0;
        return 1;
    }
    return 0;
}

/* A fresh buffer of at least bytes, bound to GL_ARRAY_BUFFER. */
static int stream_renew(qgl_context *ctx, size_t bytes)
{
    struct qgl__gl *gl = &ctx->gl;
    qgl__stream *s = &ctx->stream;
    const GLbitfield persistent = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    size_t size = bytes > QGL__STREAM_SIZE ? bytes : QGL__STREAM_SIZE;
    if (s->persistent) {
        retire(ctx);
        if (reuse(ctx, bytes))
            return 1;
    }
    if (!s->buf)
        gl->GenBuffers(1, &s->buf);
    gl->BindBuffer(GL_ARRAY_BUFFER, s->buf);
    s->head = 0;
    s->size = size;
    if (s->persistent) {
        gl->BufferStorage(GL_ARRAY_BUFFER, (GLsizeiptr)size, NULL, persistent);
        s->map = gl->MapBufferRange(GL_ARRAY_BUFFER, 0, (GLsizeiptr)size, persistent);
        return s->map != NULL;
    }
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)size, NULL, GL_STREAM_DRAW);
    return 1;
}

void qgl__stream_init(qgl_context *ctx)
{
    struct qgl__gl *gl = &ctx->gl;
    ctx->stream.persistent = gl->BufferStorage && gl->MapBufferRange && gl->UnmapBuffer &&
                             (ctx->version >= 44 || qgl__has_extension(ctx, "GL_ARB_buffer_storage"));
}

void *qgl__stream_begin(qgl_context *ctx, size_t bytes, size_t *offset)
{
    struct qgl__gl *gl = &ctx->gl;
    qgl__stream *s = &ctx->stream;
    bytes = (bytes + 15) & ~(size_t)15;
    if (!s->buf || s->head + bytes > s->size) {
        if (!stream_renew(ctx, bytes)) {
            stream_release(ctx);
            return NULL;
        }
    } else {
        gl->BindBuffer(GL_ARRAY_BUFFER, s->buf);
    }
    *offset = s->head;
    s->head += bytes;
    if (s->persistent)
        return s->map + *offset;
    const GLbitfield unsync = GL_MAP_WRITE_BIT | GL_MAP_UNSYNCHRONIZED_BIT | GL_MAP_INVALIDATE_RANGE_BIT;
    return gl->MapBufferRange(GL_ARRAY_BUFFER, (GLintptr)*offset, (GLsizeiptr)bytes, unsync);
}

void qgl__stream_end(qgl_context *ctx)
{
    if (!ctx->stream.persistent)
        ctx->gl.UnmapBuffer(GL_ARRAY_BUFFER);
}

void qgl__stream_free(qgl_context *ctx)
{
    stream_release(ctx);
    while (ctx->stream.npool)
        pool_drop(ctx, ctx->stream.npool - 1);
}
