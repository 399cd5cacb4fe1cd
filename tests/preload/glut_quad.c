/* glut_quad.c: a freeglut program that draws ref_quad.h's quad and saves what it drew.
 *
 * An ordinary legacy program (freeglut window, glBegin/glEnd, linked against libGL and
 * libglut); test_x11 runs it with libquadgl-preload.so preloaded. It draws one frame, reads
 * it back and writes it as a PPM to the file named by PT_SHOT. */
#include <GL/freeglut.h>
#include <stdio.h>
#include <stdlib.h>

#include "ref_quad.h"

static void display(void)
{
    static unsigned char rgb[REF_SIZE * REF_SIZE * 3];
    const char *path = getenv("PT_SHOT");
    FILE *f;
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor3fv(ref_c[i]);
        glVertex2fv(ref_v[i]);
    }
    glEnd();
    glFinish();
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, REF_SIZE, REF_SIZE, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    if (!path || !(f = fopen(path, "wb")))
        exit(2);
    fprintf(f, "P6\n%d %d\n255\n", REF_SIZE, REF_SIZE);
    fwrite(rgb, 3, REF_SIZE * REF_SIZE, f); /* rows from the bottom, as GL reads them */
    fclose(f);
    exit(0);
}

int main(int argc, char **argv)
{
    glutInit(&argc, argv);
    glutInitDisplayMode(GLUT_RGB | GLUT_SINGLE);
    glutInitWindowSize(REF_SIZE, REF_SIZE);
    glutCreateWindow("quadgl glut test");
    glutDisplayFunc(display);
    glutMainLoop();
    return 1;
}
