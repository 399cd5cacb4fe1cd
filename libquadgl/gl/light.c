/* light.c: fixed-function lighting of a quad's corners on the CPU, for the planner alone.
 *
 * The shader path lights each corner in its vertex shader (shader.c's vs_lighting) and
 * interpolates the lit colours with the mean value weights; the driver's split lights the
 * same corners and interpolates them over its two triangles. Both interpolate the same four
 * colours, so whether the split shows the same picture is the question qgl__gain_limit
 * answers for vertex colours, asked of the lit ones. This computes them as the shader does
 * (the same equation, in double), from the light and material values read from the driver
 * once per change of them (QGL__D_FFP, QGL__D_LIGHT) and the normal matrix once per change
 * of the model-view (QGL__D_XFORM). Nothing here draws: a colour that came out slightly
 * different would move a bound, never a pixel. */
#include <math.h>
#include <string.h>

#include "gl_internal.h"

int qgl__same_material(const qgl__verts *v, const size_t idx[4])
{
    const float *m = v->mat + QGL__MATERIAL_FLOATS * idx[0];
    for (int c = 1; c < 4; c++)
        if (memcmp(m, v->mat + QGL__MATERIAL_FLOATS * idx[c], QGL__MATERIAL_FLOATS * sizeof(float)))
            return 0;
    return 1;
}

/* Each query makes the driver flush what it holds (Mesa: its immediate-mode vertices), so
 * only what changed is asked for: materials after a glMaterial (QGL__D_LIGHT), the lights too
 * after a change of the fixed-function state; the back material only under two-sided
 * lighting. */
static void fetch_materials(qgl_context *ctx, const qgl__key *k)
{
    struct qgl__gl *gl = &ctx->gl;
    qgl__lightvals *lv = &ctx->lightvals;
    static const GLenum mat_pnames[4] = {GL_EMISSION, GL_AMBIENT, GL_DIFFUSE, GL_SPECULAR};
    for (int f = 0; f < ((k->flags & QGL__KF_TWO_SIDE) ? 2 : 1); f++) {
        for (int p = 0; p < 4; p++)
            gl->GetMaterialfv(f ? GL_BACK : GL_FRONT, mat_pnames[p], lv->mat[f][p]);
        gl->GetMaterialfv(f ? GL_BACK : GL_FRONT, GL_SHININESS, &lv->shininess[f]);
    }
}

/* A glMaterial the driver took outside glBegin/glEnd, into the copy, so that the planner
 * need not ask again (programs set materials between parts, many times a frame). 0 where the
 * copy is not whole yet or the driver may refuse the call (GL's errors: a bad face, name or
 * shininess): then the copy is read again. Under colour material the driver keeps the
 * tracked values apart from glMaterial, but the planner takes those from the colour, and
 * turning colour material off re-reads the copy (a change of the fixed-function state). */
int qgl__material_set(qgl_context *ctx, GLenum face, GLenum pname, const float v[4])
{
    qgl__lightvals *lv = &ctx->lightvals;
    static const GLenum names[4] = {GL_EMISSION, GL_AMBIENT, GL_DIFFUSE, GL_SPECULAR};
    int f0 = face == GL_BACK, f1 = face == GL_FRONT ? 0 : 1;
    if (!lv->materials_valid || (face != GL_FRONT && face != GL_BACK && face != GL_FRONT_AND_BACK))
        return 0;
    if (pname == GL_SHININESS && !(v[0] >= 0 && v[0] <= 128))
        return 0;
    int known = pname == GL_SHININESS || pname == GL_AMBIENT_AND_DIFFUSE || pname == GL_COLOR_INDEXES;
    for (int p = 0; p < 4; p++)
        known |= pname == names[p];
    if (!known)
        return 0;
    for (int f = f0; f <= f1; f++) {
        if (pname == GL_SHININESS)
            lv->shininess[f] = v[0];
        for (int p = 0; p < 4; p++)
            if (pname == names[p] || (pname == GL_AMBIENT_AND_DIFFUSE && (p == 1 || p == 2)))
                memcpy(lv->mat[f][p], v, 4 * sizeof(float));
    }
    return 1;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(double a[3])
{
    double l = sqrt(dot3(a, a));
    if (l > 0)
        a[0] /= l, a[1] /= l, a[2] /= l;
}

static void fetch_lights(qgl_context *ctx, const qgl__key *k)
{
    struct qgl__gl *gl = &ctx->gl;
    qgl__lightvals *lv = &ctx->lightvals;
    for (int i = 0; i < 8; i++) {
        if (!((k->lights >> i) & 1))
            continue;
        GLenum l = GL_LIGHT0 + (GLenum)i;
        qgl__lightval *L = &lv->light[i];
        GLfloat cutoff = 180;
        gl->GetLightfv(l, GL_AMBIENT, L->amb);
        gl->GetLightfv(l, GL_DIFFUSE, L->dif);
        gl->GetLightfv(l, GL_SPECULAR, L->spe);
        gl->GetLightfv(l, GL_POSITION, L->pos);
        gl->GetLightfv(l, GL_SPOT_DIRECTION, L->dir);
        gl->GetLightfv(l, GL_SPOT_EXPONENT, &L->exponent);
        gl->GetLightfv(l, GL_SPOT_CUTOFF, &cutoff);
        gl->GetLightfv(l, GL_CONSTANT_ATTENUATION, &L->att[0]);
        gl->GetLightfv(l, GL_LINEAR_ATTENUATION, &L->att[1]);
        gl->GetLightfv(l, GL_QUADRATIC_ATTENUATION, &L->att[2]);
        L->cos_cutoff = (float)cos(cutoff * (M_PI / 180));
        for (int c = 0; c < 3; c++) {
            L->at[c] = L->pos[3] != 0 ? L->pos[c] / L->pos[3] : 0; /* in float, as the shader divides */
            L->to[c] = L->pos[c];
            L->spot[c] = L->dir[c];
        }
        normalize3(L->to);
        normalize3(L->spot);
        L->half[0] = L->to[0], L->half[1] = L->to[1], L->half[2] = L->to[2] + 1;
        normalize3(L->half);
    }
    gl->GetFloatv(GL_LIGHT_MODEL_AMBIENT, lv->model_ambient);
}

/* The normal matrix, the transpose of the model-view's upper 3 x 3 inverse (n_eye[r] is row r
 * of it times n), and GL_RESCALE_NORMAL's factor; 0 when singular. */
static int normal_matrix(const double mv[16], double nm[3][3], double *rescale)
{
    double m[3][3], inv[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            m[r][c] = mv[4 * c + r];
    inv[0][0] = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    inv[0][1] = m[0][2] * m[2][1] - m[0][1] * m[2][2];
    inv[0][2] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    inv[1][0] = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    inv[1][1] = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    inv[1][2] = m[0][2] * m[1][0] - m[0][0] * m[1][2];
    inv[2][0] = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    inv[2][1] = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    inv[2][2] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    double det = m[0][0] * inv[0][0] + m[0][1] * inv[1][0] + m[0][2] * inv[2][0];
    if (!(fabs(det) > 1e-300) || !isfinite(det))
        return 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            nm[r][c] = inv[c][r] / det; /* n_eye = (M^-1)^T n */
    double len = sqrt(inv[2][0] * inv[2][0] + inv[2][1] * inv[2][1] + inv[2][2] * inv[2][2]) / fabs(det);
    *rescale = len > 0 ? 1 / len : 1;
    return 1;
}

/* One face's colours at one vertex (n already facing it): primary RGBA, then the secondary
 * RGB (zero unless the specular term is separate), clamped as the vertex shader clamps. */
static void light_vertex(const qgl__key *k, const qgl__lightvals *lv, const float mat[4][4], float shininess,
                         const double n[3], const double eye[3], float out[7])
{
    double amb[3] = {0}, dif[3] = {0}, spe[3] = {0}, V[3] = {0, 0, 1};
    if (k->flags & QGL__KF_LOCAL_VIEWER) {
        V[0] = -eye[0], V[1] = -eye[1], V[2] = -eye[2];
        normalize3(V);
    }
    int local = (k->flags & QGL__KF_LOCAL_VIEWER) != 0;
    for (unsigned bits = k->lights; bits; bits &= bits - 1) {
        int i = __builtin_ctz(bits), positional = (k->light_pos >> i) & 1;
        const qgl__lightval *L = &lv->light[i];
        double VP[3], att = 1;
        if (positional) {
            for (int c = 0; c < 3; c++)
                VP[c] = L->at[c] - eye[c];
            double d = sqrt(dot3(VP, VP));
            if (d > 0)
                VP[0] /= d, VP[1] /= d, VP[2] /= d;
            att = 1 / (L->att[0] + d * (L->att[1] + d * L->att[2]));
        } else
            memcpy(VP, L->to, sizeof VP);
        if ((k->light_spot >> i) & 1) {
            double sd = -dot3(VP, L->spot);
            att *= sd >= L->cos_cutoff ? pow(fmax(sd, 0), L->exponent) : 0;
        }
        double nv = dot3(n, VP);
        for (int c = 0; c < 3; c++)
            amb[c] += att * L->amb[c];
        if (nv > 0) {
            double h[3];
            if (positional || local) {
                h[0] = VP[0] + V[0], h[1] = VP[1] + V[1], h[2] = VP[2] + V[2];
                normalize3(h);
            } else
                memcpy(h, L->half, sizeof h);
            double nh = fmax(dot3(n, h), 0);
            double s = att * (nh > 0 ? pow(nh, shininess) : (shininess == 0 ? 1 : 0));
            for (int c = 0; c < 3; c++) {
                dif[c] += att * nv * L->dif[c];
                spe[c] += s * L->spe[c];
            }
        }
    }
    int separate = (k->flags & QGL__KF_SEPARATE_SPEC) != 0;
    for (int c = 0; c < 3; c++) {
        double p = mat[0][c] + mat[1][c] * lv->model_ambient[c] + amb[c] * mat[1][c] + dif[c] * mat[2][c];
        double s = spe[c] * mat[3][c];
        out[c] = (float)qgl__clamp01(separate ? p : p + s);
        out[4 + c] = separate ? (float)qgl__clamp01(s) : 0;
    }
    out[3] = (float)qgl__clamp01(mat[2][3]);
}

int qgl__lit_colours(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                     float out[2][4 * QGL__LIT_FLOATS])
{
    const qgl__key *k = &st->ffp;
    qgl__lightvals *lv = &ctx->lightvals;
    if (!lv->current_valid && (!(v->mask & QGL__A_NORMAL) || (k->cm_mode && !(v->mask & QGL__A_COLOR)))) {
        /* what the batch does not hold is the driver's current value, one for all its vertices */
        ctx->gl.GetFloatv(GL_CURRENT_NORMAL, lv->cur_normal);
        ctx->gl.GetFloatv(GL_CURRENT_COLOR, lv->cur_colour);
        lv->current_valid = 1;
    }
    if (!lv->lights_valid) {
        fetch_lights(ctx, k);
        lv->lights_valid = 1;
    }
    if (!lv->materials_valid) {
        fetch_materials(ctx, k);
        lv->materials_valid = 1;
    }
    if (!lv->normal_valid) {
        lv->normal_ok = normal_matrix(st->xf.modelview, lv->nmat, &lv->rescale);
        lv->normal_valid = 1;
    }
    if (!lv->normal_ok)
        return 0;
    /* per-vertex materials: the planner judges only quads whose corners share one */
    const float *vmat = (v->mask & QGL__A_MATERIAL) ? v->mat + QGL__MATERIAL_FLOATS * idx[0] : NULL;
    int faces = (k->flags & QGL__KF_TWO_SIDE) ? 2 : 1;
    for (int f = 0; f < faces; f++) {
        float mat[4][4], shininess = lv->shininess[f];
        memcpy(mat, lv->mat[f], sizeof mat);
        if (vmat) { /* its layout: ambient, diffuse, specular, emission per face, shininesses */
            static const int from[4] = {12, 0, 4, 8};
            for (int p = 0; p < 4; p++)
                memcpy(mat[p], vmat + 16 * f + from[p], 4 * sizeof(float));
            shininess = vmat[32 + f];
        }
        for (int c = 0; c < 4; c++) {
            size_t i = idx[c];
            const float *o = v->pos + 4 * i;
            const float *nr = (v->mask & QGL__A_NORMAL) ? v->nrm + 3 * i : lv->cur_normal;
            double n[3], eye[3];
            for (int r = 0; r < 3; r++) {
                n[r] = lv->nmat[r][0] * nr[0] + lv->nmat[r][1] * nr[1] + lv->nmat[r][2] * nr[2];
                /* the shader's eye position: (M v).xyz, not divided by its w */
                eye[r] = st->xf.modelview[r] * o[0] + st->xf.modelview[4 + r] * o[1] + st->xf.modelview[8 + r] * o[2] +
                         st->xf.modelview[12 + r] * o[3];
            }
            if (k->flags & QGL__KF_NORMALIZE)
                normalize3(n);
            else if (k->flags & QGL__KF_RESCALE)
                n[0] *= lv->rescale, n[1] *= lv->rescale, n[2] *= lv->rescale;
            if (f)
                n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
            if (k->cm_mode && (k->cm_face & (1 << f))) {
                const float *col = (v->mask & QGL__A_COLOR) ? v->col + 4 * i : lv->cur_colour;
                static const int tracked[6][2] = {{-1, -1}, {0, -1}, {1, -1}, {2, -1}, {3, -1}, {1, 2}};
                for (int t = 0; t < 2; t++)
                    if (tracked[k->cm_mode][t] >= 0)
                        memcpy(mat[tracked[k->cm_mode][t]], col, 4 * sizeof(float));
            }
            light_vertex(k, lv, (const float(*)[4])mat, shininess, n, eye, out[f] + QGL__LIT_FLOATS * c);
        }
    }
    return faces;
}
