/* scenes.c: small quad meshes shared by the GL tests. */
#include "scenes.h"

#include <stdlib.h>

static float frand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)((*s >> 8) & 0xffff) / 65535.0f;
}

static void put(sc_mesh *m, float x, float y, float z, const float c[4], float u, float v)
{
    int i = m->nverts++;
    m->pos[i][0] = x, m->pos[i][1] = y, m->pos[i][2] = z;
    for (int k = 0; k < 4; k++)
        m->col[i][k] = c[k];
    m->uv[i][0] = u, m->uv[i][1] = v;
}

static void affine_vertex(sc_mesh *m, float s, float t)
{
    float x = -1 + 2 * s + 0.3f * t, y = -1 + 2 * t;
    float c[4] = {0.5f + 0.35f * x, 0.5f + 0.3f * y, 0.5f - 0.2f * x + 0.2f * y, 0.8f + 0.1f * x};
    put(m, x, y, 0, c, 0.7f * x + 0.2f * y, -0.2f * x + 0.9f * y);
}

void sc_affine_grid(sc_mesh *m, int n, int strips)
{
    m->nverts = 0;
    m->strip_rows = strips ? n : 0;
    m->strip_cols = n;
    for (int j = 0; j < n; j++) {
        if (strips) {
            for (int i = 0; i <= n; i++) {
                affine_vertex(m, (float)i / n, (float)j / n);
                affine_vertex(m, (float)i / n, (float)(j + 1) / n);
            }
            continue;
        }
        for (int i = 0; i < n; i++) {
            affine_vertex(m, (float)i / n, (float)j / n);
            affine_vertex(m, (float)(i + 1) / n, (float)j / n);
            affine_vertex(m, (float)(i + 1) / n, (float)(j + 1) / n);
            affine_vertex(m, (float)i / n, (float)(j + 1) / n);
        }
    }
}

void sc_jitter_grid(sc_mesh *m, int n, float jit, float zj, unsigned seed, int strips)
{
    float P[33][33][3], C[33][33][4];
    unsigned s = seed;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            int edge = i == 0 || j == 0 || i == n || j == n;
            float dx = edge ? 0 : (frand(&s) - 0.5f) * 2 * jit, dy = edge ? 0 : (frand(&s) - 0.5f) * 2 * jit;
            P[j][i][0] = -0.9f + 1.8f * (i + dx) / n;
            P[j][i][1] = -0.9f + 1.8f * (j + dy) / n;
            P[j][i][2] = (frand(&s) - 0.5f) * zj;
            for (int k = 0; k < 3; k++)
                C[j][i][k] = frand(&s);
            C[j][i][3] = 1;
        }
    m->nverts = 0;
    m->strip_rows = strips ? n : 0;
    m->strip_cols = n;
    static const int qi[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int j = 0; j < n; j++) {
        if (strips) {
            for (int i = 0; i <= n; i++) {
                put(m, P[j][i][0], P[j][i][1], P[j][i][2], C[j][i], 0, 0);
                put(m, P[j + 1][i][0], P[j + 1][i][1], P[j + 1][i][2], C[j + 1][i], 0, 0);
            }
            continue;
        }
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 4; c++) {
                int a = i + qi[c][0], b = j + qi[c][1];
                put(m, P[b][a][0], P[b][a][1], P[b][a][2], C[b][a], 0, 0);
            }
    }
}

static void emit(const sc_mesh *m, int i, int native, int use_color, int use_uv)
{
    if (native) {
        if (use_color)
            glColor4fv(m->col[i]);
        if (use_uv)
            glTexCoord2fv(m->uv[i]);
        glVertex3fv(m->pos[i]);
    } else {
        if (use_color)
            qglColor4fv(m->col[i]);
        if (use_uv)
            qglTexCoord2fv(m->uv[i]);
        qglVertex3fv(m->pos[i]);
    }
}

void sc_draw(const sc_mesh *m, int native, int use_color, int use_uv)
{
    if (m->strip_rows) {
        int per = 2 * (m->strip_cols + 1);
        for (int r = 0; r < m->strip_rows; r++) {
            native ? glBegin(GL_QUAD_STRIP) : qglBegin(GL_QUAD_STRIP);
            for (int i = 0; i < per; i++)
                emit(m, r * per + i, native, use_color, use_uv);
            native ? glEnd() : qglEnd();
        }
        return;
    }
    native ? glBegin(GL_QUADS) : qglBegin(GL_QUADS);
    for (int i = 0; i < m->nverts; i++)
        emit(m, i, native, use_color, use_uv);
    native ? glEnd() : qglEnd();
}

unsigned sc_texture(int with_alpha)
{
    enum { N = 64 };
    static unsigned char tex[N][N][4];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            tex[y][x][0] = (unsigned char)(x * 4);
            tex[y][x][1] = (unsigned char)(y * 4);
            tex[y][x][2] = (unsigned char)(64 + (x + y) * 2);
            tex[y][x][3] = (unsigned char)(255 - x * 2);
        }
    GLuint id;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glTexImage2D(GL_TEXTURE_2D, 0, with_alpha ? GL_RGBA8 : GL_RGB8, N, N, 0, GL_RGBA, GL_UNSIGNED_BYTE, tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return id;
}

void sc_camera(float angle_x, float angle_z)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.6, 0.6, -0.6, 0.6, 1, 10);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glTranslatef(0, 0, -2.6f);
    glRotatef(angle_x, 1, 0, 0);
    glRotatef(angle_z, 0, 0, 1);
}

int sc_diff(const th_ctx *t, const unsigned char *a, const unsigned char *b, int tol, int *over)
{
    int worst = 0, n = 0;
    for (int i = 0; i < t->w * t->h; i++) {
        int bad = 0;
        for (int k = 0; k < 4; k++) {
            int d = abs(a[4 * i + k] - b[4 * i + k]);
            worst = d > worst ? d : worst;
            bad |= d > tol;
        }
        n += bad;
    }
    if (over)
        *over = n;
    return worst;
}

void sc_coverage_run(th_ctx *t, const sc_mesh *m, sc_coverage *out)
{
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glColor4f(0.25f, 0.25f, 0.25f, 0.25f);
    glClear(GL_COLOR_BUFFER_BIT);
    sc_draw(m, 1, 0, 0);
    out->native = th_snapshot(t);
    glClear(GL_COLOR_BUFFER_BIT);
    qgl_gl_reset_stats(t->qgl);
    sc_draw(m, 0, 0, 0);
    out->ours = th_snapshot(t);
    qgl_gl_stats(t->qgl, &out->st);
    out->twice = out->differ = out->inside = 0;
    for (int i = 0; i < t->w * t->h; i++) {
        out->twice += out->ours[4 * i] > 80;
        out->differ += (out->ours[4 * i] != 0) != (out->native[4 * i] != 0);
        out->inside += out->native[4 * i] != 0;
    }
}

const float sc_corner_colors[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};

void sc_draw_quad(const float p[4][3])
{
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        qglColor4fv(sc_corner_colors[i]);
        qglVertex3fv(p[i]);
    }
    qglEnd();
}
