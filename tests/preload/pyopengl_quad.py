"""pyopengl_quad.py: ref_quad.h's quad drawn from Python through PyOpenGL and GLUT.

PyOpenGL opens libGL.so.1 itself (ctypes, dlopen) and finds every function with dlsym, the
path the preload library must redirect. Run with /usr/bin/python3 (the system's PyOpenGL);
writes the frame as a PPM to the file named by PT_SHOT and returns from the GLUT main loop,
so the process ends normally (quadgl's statistics line is printed at exit).
"""
import os
import sys

from OpenGL import GL, GLUT

SIZE = 64
V = [(-0.8, -0.9), (0.7, -0.6), (0.5, 0.8), (-0.9, 0.5)]
C = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)]


def display():
    GL.glClearColor(0, 0, 0, 1)
    GL.glClear(GL.GL_COLOR_BUFFER_BIT)
    GL.glBegin(GL.GL_QUADS)
    for v, c in zip(V, C):
        GL.glColor3f(*c)
        GL.glVertex2f(*v)
    GL.glEnd()
    GL.glFinish()
    GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 1)
    data = GL.glReadPixels(0, 0, SIZE, SIZE, GL.GL_RGB, GL.GL_UNSIGNED_BYTE)
    with open(os.environ["PT_SHOT"], "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (SIZE, SIZE))
        f.write(bytes(data))
    GLUT.glutLeaveMainLoop()


GLUT.glutInit(sys.argv)
GLUT.glutSetOption(GLUT.GLUT_ACTION_ON_WINDOW_CLOSE, GLUT.GLUT_ACTION_GLUTMAINLOOP_RETURNS)
GLUT.glutInitDisplayMode(GLUT.GLUT_RGB | GLUT.GLUT_SINGLE)
GLUT.glutInitWindowSize(SIZE, SIZE)
GLUT.glutCreateWindow(b"quadgl pyopengl test")
GLUT.glutDisplayFunc(display)
GLUT.glutMainLoop()
