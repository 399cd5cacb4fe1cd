/* Scene files: every shipped scene loads; bad scene text and bad images give an error that
 * names the file and the line ("FILE:LINE: ..."), and never a half-built scene. */
#include "render_test.h"

#include <dirent.h>
#include <unistd.h>
#ifdef QGL_HAVE_IMAGES
#include "qgl_image.h"
#endif

#define HEADER "size 32 32\ncamera perspective 40 0.5 10\nlookat 0 0 3 0 0 0 0 1 0\n"

static qgl_sw_scene_load_desc loader(void)
{
    qgl_sw_scene_load_desc d = {0};
#ifdef QGL_HAVE_IMAGES
    d.load_image = qgl_image_load_texture;
#endif
    return d;
}

/* text must fail with an error containing want. */
static void bad(const char *name, const char *text, const char *want)
{
    char err[512] = "";
    qgl_sw_scene *s = (qgl_sw_scene *)1;
    qgl_sw_scene_load_desc d = loader();
    int r = qgl_sw_scene_parse(text, name, &d, &s, err, sizeof err);
    printf("%-28s -> %s\n", name, err);
    CHECK(r < 0 && s == NULL, "%s: should fail", name);
    CHECK(strstr(err, want) != NULL, "%s: error '%s' does not contain '%s'", name, err, want);
}

static void shipped_scenes(void)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/data/scenes", QGL_SOURCE_DIR);
    DIR *d = opendir(dir);
    CHECK(d != NULL, "cannot open %s", dir);
    if (!d)
        return;
    int n = 0;
    qgl_sw_scene_load_desc ld = loader();
    for (struct dirent *e; (e = readdir(d));) {
        size_t l = strlen(e->d_name);
        if (l < 6 || strcmp(e->d_name + l - 6, ".scene"))
            continue;
        char path[2048], err[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        qgl_sw_scene *s = NULL;
        int r = qgl_sw_scene_load(path, &ld, &s, err, sizeof err);
#ifndef QGL_HAVE_IMAGES
        if (r && strstr(err, "OpenImageIO"))
            continue;
#endif
        CHECK(r == 0 && s && s->nquads > 0, "%s: %s", path, err);
        qgl_sw_scene_free(s);
        n++;
    }
    closedir(d);
    printf("%d shipped scenes load\n", n);
    CHECK(n >= 10, "only %d scenes", n);
}

int main(void)
{
    shipped_scenes();
    bad("unknown.scene", HEADER "attributes uv\ntextur checker 8 2\n", "unknown.scene:5: unknown keyword 'textur'");
    bad("number.scene", HEADER "attributes color\nvertex 0 0 zero 1 0 0\n", "number.scene:5: 'zero' is not a finite number");
    bad("count.scene", HEADER "attributes color\nvertex 0 0 0 1 0\n", "count.scene:5: vertex needs x y z and 3 attribute");
    bad("index.scene", HEADER "attributes color\nvertex 0 0 0 1 0 0\nquad 0 0 0 7\n", "index.scene:6: quad: vertex index '7' out of range");
    bad("order.scene", HEADER "vertex 0 0 0\n", "order.scene:4: 'attributes' must come before");
    bad("camera.scene", "camera perspective 200 1 2\n", "camera.scene:1: camera perspective: need 0 < FOVY < 180");
    bad("empty.scene", HEADER "attributes color\n", "empty.scene:4: the scene has no quads");
    bad("notex.scene", HEADER "attributes uv\nvertex 0 0 0 0 0\nquad 0 0 0 0\n", "notex.scene:4: uv attributes need a 'texture' line");
    bad("sphere.scene", HEADER "attributes uv\ntexture checker 8 2\nsphere 1 8 1\n", "sphere.scene:6: '1' must be an integer in [2, 2000]");

    char err[512];
    qgl_sw_scene *s = NULL;
    qgl_sw_scene_load_desc ld = loader();
    int r = qgl_sw_scene_load("/nonexistent/x.scene", &ld, &s, err, sizeof err);
    printf("%-28s -> %s\n", "missing file", err);
    CHECK(r < 0 && strstr(err, "/nonexistent/x.scene:0: cannot open"), "missing file: %s", err);

#ifdef QGL_HAVE_IMAGES
    /* an image that does not exist, and one that is not an image */
    bad("/tmp/qgl_missing.scene", HEADER "attributes uv\ntexture image no_such_file.png\n",
        "/tmp/qgl_missing.scene:5: texture image '/tmp/no_such_file.png'");
    char junk[] = "/tmp/qgl_junk_XXXXXX.png";
    int fd = mkstemps(junk, 4);
    CHECK(fd >= 0, "mkstemps");
    if (fd >= 0) {
        CHECK(write(fd, "not a png at all", 16) == 16, "write");
        close(fd);
        char text[1024], want[600];
        snprintf(text, sizeof text, HEADER "attributes uv\n\ntexture image %s\n", junk);
        snprintf(want, sizeof want, "/tmp/junk.scene:6: texture image '%s'", junk);
        bad("/tmp/junk.scene", text, want);
        unlink(junk);
    }
#else
    bad("noimages.scene", HEADER "attributes uv\ntexture image x.png\n", "noimages.scene:5: texture image: this program cannot read image files");
#endif
    return failures ? 1 : 0;
}
