/* present_swap_group: NVIDIA's hardware swap synchronisation (GLX_NV_swap_group) for a
 * presentation window (see present_window.h). A swap group makes the windows in it swap
 * together on one machine; binding the group to a swap barrier makes every machine's
 * group swap together, through the frame lock (genlock) of a Quadro Sync board. Its own
 * file: GLX's headers bring the old GL 1.x declarations, which the rest of the node keeps
 * out (gl_functions.h). */
#include <stdio.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#define GLFW_EXPOSE_NATIVE_GLX
#include <GLFW/glfw3native.h>

#include "present_window.h"

typedef Bool (*query_max_fn)(Display *dpy, int screen, GLuint *max_groups, GLuint *max_barriers);
typedef Bool (*join_fn)(Display *dpy, GLXDrawable drawable, GLuint group);
typedef Bool (*bind_fn)(Display *dpy, GLuint group, GLuint barrier);

int present_swap_group_join(void *glfw_window, int group, int barrier, char *why, size_t whylen)
{
    GLFWwindow *win = glfw_window;
    Display *dpy = glfwGetX11Display();
    if (!dpy) {
        snprintf(why, whylen, "not on an X11 display (swap groups are a GLX extension)");
        return 0;
    }
    int screen = DefaultScreen(dpy);
    const char *ext = glXQueryExtensionsString(dpy, screen);
    query_max_fn query_max = (query_max_fn)glXGetProcAddressARB((const GLubyte *)"glXQueryMaxSwapGroupsNV");
    join_fn join = (join_fn)glXGetProcAddressARB((const GLubyte *)"glXJoinSwapGroupNV");
    bind_fn bind = (bind_fn)glXGetProcAddressARB((const GLubyte *)"glXBindSwapBarrierNV");
    if (!ext || !strstr(ext, "GLX_NV_swap_group") || !query_max || !join || !bind) {
        snprintf(why, whylen, "the GLX driver has no GLX_NV_swap_group (NVIDIA's professional drivers "
                 "have it)");
        return 0;
    }
    GLuint max_groups = 0, max_barriers = 0;
    if (!query_max(dpy, screen, &max_groups, &max_barriers) || (GLuint)group > max_groups) {
        snprintf(why, whylen, "swap group %d asked, the driver offers %u", group, max_groups);
        return 0;
    }
    GLXDrawable drawable = glfwGetGLXWindow(win);
    if (!drawable)
        drawable = glfwGetX11Window(win);
    if (!join(dpy, drawable, (GLuint)group)) {
        snprintf(why, whylen, "glXJoinSwapGroupNV refused group %d", group);
        return 0;
    }
    if (barrier <= 0)
        snprintf(why, whylen, "no barrier asked: this machine's windows only");
    else if ((GLuint)barrier > max_barriers)
        snprintf(why, whylen, "barrier %d not bound: the driver offers %u barriers (a Quadro Sync board "
                 "with frame lock provides them)", barrier, max_barriers);
    else if (!bind(dpy, (GLuint)group, (GLuint)barrier))
        snprintf(why, whylen, "barrier %d not bound: glXBindSwapBarrierNV refused it", barrier);
    else
        snprintf(why, whylen, "bound to barrier %d", barrier);
    return 1;
}
