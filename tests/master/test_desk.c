/* Desk simulator: the control-to-pose maths and the window's picture without a window,
 * then the real GLFW window under a private Xvfb (skipped with a message where Xvfb is not
 * installed), whose pixels must show the picture rather than black. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <GLFW/glfw3.h>

#include "input/input.h"
#include "input/desk_view.h"
#include "input/input_desk.h"
#include "interaction.h"

static int same(const uint8_t *rgb, int w, int x, int y, const uint8_t c[3])
{
    return memcmp(rgb + ((size_t)y * w + x) * 3, c, 3) == 0;
}

/* The picture: key help on the left, the head and the wand where they are on the map. */
static void test_view(void **state)
{
    enum { W = 360, H = 240 };
    static uint8_t rgb[W * H * 3];
    input_source_state st = {0};
    st.head = (input_pose){.valid = 1, .position = {1.0f, 1.7f, -0.5f}, .rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    st.wand = (input_pose){.valid = 1, .position = {-1.0f, 1.45f, 0.5f}, .rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    desk_view_draw(rgb, W, H, &st);
    int hx, hy, wx, wy, rx, ry;
    desk_view_map_pixel(W, H, 1.0f, -0.5f, &hx, &hy);
    desk_view_map_pixel(W, H, -1.0f, 0.5f, &wx, &wy);
    desk_view_map_pixel(W, H, -1.0f, 0.25f, &rx, &ry); /* half way along the ray, toward -Z */
    assert_true(hx > W / 2 && hx < W && hy > 0 && hy < H);
    assert_true(same(rgb, W, hx, hy, desk_view_head_color));
    assert_true(same(rgb, W, wx, wy, desk_view_wand_color));
    assert_true(same(rgb, W, rx, ry, desk_view_wand_color));
    assert_true(hx > wx && hy < wy); /* right of and in front of the wand, as placed */
    int text = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W / 2; x++)
            text += same(rgb, W, x, y, desk_view_text_color);
    assert_true(text > 500); /* eleven lines of key help */
    /* The head moves: the dot moves with it. */
    st.head.position[0] = -0.5f;
    desk_view_draw(rgb, W, H, &st);
    assert_false(same(rgb, W, hx, hy, desk_view_head_color));
    desk_view_map_pixel(W, H, -0.5f, -0.5f, &hx, &hy);
    assert_true(same(rgb, W, hx, hy, desk_view_head_color));
}

static void test_step(void **state)
{
    input_desk_state ds = {0};
    input_source_state st = {0};
    input_desk_controls c = {.cursor = {0.5f, 0.5f}};
    input_desk_step(&ds, &c, 0.0, &st, 1.0);
    assert_float_equal(st.head.position[1], 1.7f, 0);
    /* centred mouse: wand points along -Z, 0.4 m in front of and 0.25 m below the eyes */
    assert_float_equal(st.wand.rotation[8], 1.0f, 1e-6);
    assert_float_equal(st.wand.position[2], -0.4f, 1e-6);
    assert_float_equal(st.wand.position[1], 1.45f, 1e-6);
    /* W for 0.5 s: 0.5 m forward; the wand comes along */
    c.forward = 1;
    input_desk_step(&ds, &c, 0.5, &st, 1.5);
    assert_float_equal(st.head.position[2], -0.5f, 1e-6);
    assert_float_equal(st.wand.position[2], -0.9f, 1e-6);
    assert_float_equal(st.head.time, 1.5, 0);
    c.forward = 0;
    /* mouse at the left edge: a quarter turn left, the wand points along -X */
    c.cursor[0] = 0.0f;
    input_desk_step(&ds, &c, 0.1, &st, 1.6);
    assert_float_equal(-st.wand.rotation[6], -1.0f, 1e-6);
    assert_float_equal(st.wand.position[0], -0.4f, 1e-5);
    /* mouse at the top: pitched 45 degrees up */
    c.cursor[0] = 0.5f;
    c.cursor[1] = 0.0f;
    input_desk_step(&ds, &c, 0.1, &st, 1.7);
    assert_float_equal(-st.wand.rotation[7], sinf(0.78539816f), 1e-6);
    /* the wheel sets the reach, and with it the fly speed: 4 steps = +0.2 m */
    c.scroll = 4;
    input_desk_step(&ds, &c, 0.1, &st, 1.8);
    assert_float_equal(st.wand.position[2] - st.head.position[2], -0.6f, 1e-5);
    interaction_desc id = {0};
    assert_true(interaction_speed(&id, 0.6f) > interaction_speed(&id, 0.4f));
    /* buttons and axes pass through with press edges */
    c.scroll = 0;
    c.buttons = 1u << INPUT_BUTTON_R;
    c.axes[1] = 1.0f;
    input_desk_step(&ds, &c, 0.1, &st, 1.9);
    assert_int_equal(st.pressed, 1u << INPUT_BUTTON_R);
    assert_float_equal(st.axes[INPUT_AXIS_Y], 1.0f, 0);
    /* the head stays inside a sane height range */
    c.down = 1;
    input_desk_step(&ds, &c, 10.0, &st, 2.0);
    assert_float_equal(st.head.position[1], 0.5f, 0);
}

static void test_window(void **state)
{
    char err[512];
    /* Without a display: one clear line. */
    char *saved = getenv("DISPLAY") ? strdup(getenv("DISPLAY")) : NULL;
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    assert_null(input_desk_open(&(input_desk_desc){0}, err, sizeof err));
    assert_non_null(strstr(err, "input desk: cannot open the desk simulator window"));
    assert_null(strchr(err, '\n'));
    free(saved);

    if (access("/usr/bin/Xvfb", X_OK) != 0) {
        printf("SKIP window part: /usr/bin/Xvfb not installed (apt-get install xvfb)\n");
        return;
    }
    int dpy = 70 + (int)(getpid() % 200);
    char name[16], sock[64];
    snprintf(name, sizeof name, ":%d", dpy);
    snprintf(sock, sizeof sock, "/tmp/.X11-unix/X%d", dpy);
    pid_t x = fork();
    if (x == 0) {
        prctl(PR_SET_PDEATHSIG, SIGTERM); /* a failed assertion must not leave it running */
        freopen("/dev/null", "w", stderr);
        execl("/usr/bin/Xvfb", "Xvfb", name, "-screen", "0", "640x480x24", "-nolisten", "tcp",
              (char *)NULL);
        _exit(127);
    }
    struct stat sb;
    for (int i = 0; i < 100 && stat(sock, &sb) != 0; i++)
        nanosleep(&(struct timespec){0, 50000000}, NULL);
    assert_int_equal(stat(sock, &sb), 0);
    setenv("DISPLAY", name, 1);

    input *in = input_create(&(input_desc){0}, err, sizeof err);
    input_source *desk = input_desk_open(&(input_desk_desc){.width = 200, .height = 100}, err, sizeof err);
    if (!desk)
        fail_msg("%s", err);
    input_add_source(in, desk, err, sizeof err);
    input_state st;
    assert_int_equal(input_poll(in, &st, err, sizeof err), 0);
    assert_true(st.head.valid && st.wand.valid);
    assert_float_equal(st.head.position[1], 1.7f, 0);
    /* Move the pointer to the window's left edge: the wand turns left. */
    GLFWwindow *w = input_desk_window(desk);
    glfwSetCursorPos(w, 0.0, 50.0);
    for (int i = 0; i < 50; i++) {
        input_poll(in, &st, err, sizeof err);
        if (st.wand.rotation[6] > 0.99f)
            break;
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    }
    assert_float_equal(st.wand.rotation[6], 1.0f, 1e-3); /* -Z column -> (-1, 0, 0) */
    /* The window shows the picture: its pixels are the view's, not black. */
    typedef void (*read_pixels_fn)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
    typedef void (*read_buffer_fn)(GLenum);
    glfwMakeContextCurrent(w);
    read_pixels_fn read_pixels = (read_pixels_fn)glfwGetProcAddress("glReadPixels");
    read_buffer_fn read_buffer = (read_buffer_fn)glfwGetProcAddress("glReadBuffer");
    if (!read_pixels || !read_buffer) {
        printf("SKIP picture part: no OpenGL on this Xvfb\n");
    } else {
        static uint8_t shown[200 * 100 * 3];
        /* The picture drawn before the last swap: Mesa's X11 software path keeps it in the
         * back buffer, and reads its front buffer as black. */
        read_buffer(GL_BACK);
        read_pixels(0, 0, 200, 100, GL_RGB, GL_UNSIGNED_BYTE, shown);
        int lit = 0, help = 0;
        for (int i = 0; i < 200 * 100; i++) {
            lit += shown[3 * i] + shown[3 * i + 1] + shown[3 * i + 2] > 0;
            help += memcmp(shown + 3 * i, desk_view_text_color, 3) == 0;
        }
        assert_int_equal(lit, 200 * 100);
        assert_true(help > 50);
    }
    /* Closing the window stops the source with one message, once. */
    glfwSetWindowShouldClose(w, GLFW_TRUE);
    assert_int_equal(input_poll(in, &st, err, sizeof err), -1);
    assert_non_null(strstr(err, "window closed"));
    assert_int_equal(input_poll(in, &st, err, sizeof err), 0);
    input_close(in);
    kill(x, SIGTERM);
    waitpid(x, NULL, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_step),
        cmocka_unit_test(test_view),
        cmocka_unit_test(test_window),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
