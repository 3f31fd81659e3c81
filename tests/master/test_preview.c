/* The master's live preview (--preview): without a display preview_open() says so in one
 * line and the master runs its session with one warning; under a private Xvfb (skipped
 * with a message where Xvfb is not installed) a real session with --preview runs to its
 * end, and the preview window of a real session's images shows exactly the unfolded
 * overview of the nodes' frames (the --overview file's pixels, not black). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

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

#include "image/image.h"
#include "preview.h"

static char dir[] = "/tmp/cavelight-pv-XXXXXX", config[200];
static cluster_config cfg;

/* Two half walls of 64 x 128 pixels, mono, png output, side by side in the overview. */
static void write_config(void)
{
    snprintf(config, sizeof config, "%s/c.json", dir);
    FILE *f = fopen(config, "w");
    assert_non_null(f);
    fputs("{\"name\": \"preview\", \"master\": {\"bind\": \"tcp://127.0.0.1:1\", \"connect\": \"tcp://127.0.0.1:1\"},\n"
          " \"security\": {\"mode\": \"insecure\"}, \"observer\": {\"home\": [0, 1.7, 0]},\n"
          " \"screens\": [\n"
          "  {\"name\": \"front-l\", \"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [0,0,-1.5],"
          " \"top_left\": [-1.5,3,-1.5], \"overview\": [0, 0]},\n"
          "  {\"name\": \"front-r\", \"bottom_left\": [0,0,-1.5], \"bottom_right\": [1.5,0,-1.5],"
          " \"top_left\": [0,3,-1.5], \"overview\": [64, 0]}],\n"
          " \"nodes\": [{\"name\": \"a\", \"screens\": [\"front-l\"], \"resolution\": [64, 128], \"output\": \"png\"},\n"
          "           {\"name\": \"b\", \"screens\": [\"front-r\"], \"resolution\": [64, 128], \"output\": \"png\"}]}\n",
          f);
    fclose(f);
    char err[512];
    if (cluster_config_load(config, &cfg, err, sizeof err) != 0)
        fail_msg("%s", err);
}

/* Runs the master on the config for 3 frames with extra options; returns its exit status
 * and its standard error in log. */
static int run_master(const char *extra, const char *env, char *log, size_t n)
{
    char cmd[4096], path[300];
    snprintf(path, sizeof path, "%s/master.log", dir);
    snprintf(cmd, sizeof cmd, "%s %s/cavelight-master --config %s --spawn-local --bind 'tcp://127.0.0.1:*' "
             "--frames 3 --out %s --lattice 8 --rsm 32 --node-args '--threads 1' %s 2> %s",
             env, CAVELIGHT_BINARY_DIR, config, dir, extra, path);
    int rc = system(cmd);
    FILE *f = fopen(path, "r");
    size_t got = f ? fread(log, 1, n - 1, f) : 0;
    log[got] = 0;
    if (f)
        fclose(f);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static int count_lines_with(const char *log, const char *what)
{
    int n = 0;
    for (const char *l = log; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        const char *end = strchr(l, '\n');
        const char *hit = strstr(l, what);
        n += hit && (!end || hit < end);
    }
    return n;
}

static void test_no_display(void **state)
{
    (void)state;
    char err[512], log[16384];
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    assert_null(preview_open(&cfg, dir, err, sizeof err));
    assert_non_null(strstr(err, "preview: no display"));
    assert_null(strchr(err, '\n'));
    /* The master warns once and runs its frames. */
    assert_int_equal(run_master("--preview --output headless", "", log, sizeof log), 0);
    assert_int_equal(count_lines_with(log, "preview"), 1);
    assert_non_null(strstr(log, "going on without it"));
    assert_non_null(strstr(log, "3 frames"));
}

static void test_window(void **state)
{
    (void)state;
    if (access("/usr/bin/Xvfb", X_OK) != 0) {
        printf("SKIP window part: /usr/bin/Xvfb not installed (apt-get install xvfb)\n");
        return;
    }
    int dpy = 300 + (int)(getpid() % 200);
    char name[16], sock[64], env[64], err[512], log[16384];
    snprintf(name, sizeof name, ":%d", dpy);
    snprintf(sock, sizeof sock, "/tmp/.X11-unix/X%d", dpy);
    pid_t x = fork();
    if (x == 0) {
        prctl(PR_SET_PDEATHSIG, SIGTERM); /* a failed assertion must not leave it running */
        freopen("/dev/null", "w", stderr);
        execl("/usr/bin/Xvfb", "Xvfb", name, "-screen", "0", "640x480x24", "-nolisten", "tcp", (char *)NULL);
        _exit(127);
    }
    struct stat sb;
    for (int i = 0; i < 100 && stat(sock, &sb) != 0; i++)
        nanosleep(&(struct timespec){0, 50000000}, NULL);
    assert_int_equal(stat(sock, &sb), 0);

    /* A whole session with the preview open runs to its end, and writes the overview. */
    snprintf(env, sizeof env, "DISPLAY=%s", name);
    char overview[300];
    snprintf(overview, sizeof overview, "--preview --output png --overview %s/overview.png", dir);
    int rc = run_master(overview, env, log, sizeof log);
    if (rc != 0)
        fail_msg("master with --preview exited %d: %s", rc, log);
    assert_non_null(strstr(log, "preview window"));
    assert_int_equal(count_lines_with(log, "going on without it"), 0);
    assert_non_null(strstr(log, "3 frames"));

    /* The window on those images shows the overview's pixels: the nodes' frames. */
    setenv("DISPLAY", name, 1);
    preview *p = preview_open(&cfg, dir, err, sizeof err);
    if (!p)
        fail_msg("%s", err);
    GLFWwindow *w = preview_window(p);
    typedef void (*read_pixels_fn)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
    typedef void (*read_buffer_fn)(GLenum);
    typedef void (*pixel_store_fn)(GLenum, GLint);
    glfwMakeContextCurrent(w);
    read_pixels_fn read_pixels = (read_pixels_fn)glfwGetProcAddress("glReadPixels");
    read_buffer_fn read_buffer = (read_buffer_fn)glfwGetProcAddress("glReadBuffer");
    pixel_store_fn pixel_store = (pixel_store_fn)glfwGetProcAddress("glPixelStorei");
    if (!read_pixels || !read_buffer || !pixel_store) {
        printf("SKIP picture part: no OpenGL on this Xvfb\n");
        preview_close(p);
    } else {
        assert_int_equal(preview_update(p, 1), 0);
        assert_int_equal(preview_screens_shown(p), 2);
        int ow, oh;
        uint8_t *want;
        snprintf(overview, sizeof overview, "%s/overview.png", dir);
        assert_int_equal(image_read_png(overview, &ow, &oh, &want, err, sizeof err), 0);
        assert_int_equal(ow, 128);
        assert_int_equal(oh, 128);
        static uint8_t shown[128 * 128 * 3];
        /* The picture drawn before the last swap (Mesa's X11 software path keeps it in the
         * back buffer), bottom row first. */
        glfwMakeContextCurrent(w);
        read_buffer(GL_BACK);
        pixel_store(GL_PACK_ALIGNMENT, 1);
        read_pixels(0, 0, ow, oh, GL_RGB, GL_UNSIGNED_BYTE, shown);
        int lit = 0, same = 0;
        for (int y = 0; y < oh; y++)
            for (int i = 0; i < ow; i++) {
                const uint8_t *s = shown + ((size_t)(oh - 1 - y) * ow + i) * 3, *o = want + ((size_t)y * ow + i) * 3;
                lit += s[0] + s[1] + s[2] > 0;
                same += memcmp(s, o, 3) == 0;
            }
        printf("preview: %d of %d pixels lit, %d equal to the overview\n", lit, ow * oh, same);
        assert_true(lit > ow * oh / 2);
        assert_int_equal(same, ow * oh);
        free(want);
        /* Closing the window ends the preview once; later updates do nothing. */
        glfwSetWindowShouldClose(w, GLFW_TRUE);
        assert_int_equal(preview_update(p, 1), 1);
        assert_int_equal(preview_update(p, 1), 0);
        preview_close(p);
    }
    kill(x, SIGTERM);
    waitpid(x, NULL, 0);
}

static int setup(void **state)
{
    (void)state;
    if (!mkdtemp(dir))
        return -1;
    write_config();
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    return system(cmd) == 0 ? 0 : -1;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_display),
        cmocka_unit_test(test_window),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
