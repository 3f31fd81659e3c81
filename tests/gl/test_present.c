/* present: the presentation pass on llvmpipe, its PNG output read back.
 *   - a viewport without a warp comes out byte for byte as rendered;
 *   - two overlapping projectors with complementary blend maps: in the overlap their light
 *     adds up to the unblended image's (display gamma 2.2), elsewhere each shows it as is;
 *   - known warps move known pixels where the closed form says: an affine 2d grid, a
 *     keystone mesh (per triangle), and a 3d point grid projected through an eye's view;
 *   - the beta map lifts black; the blend-regions variant tints only where a projector is
 *     dimmed;
 *   - window output on a private Xvfb (skipped where Xvfb is missing) puts the two eyes
 *     where each stereo mode says, read back from the window: side-by-side, top-bottom,
 *     anaglyph (red from the left eye), quad (side-by-side on llvmpipe, which has none). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cmocka.h>

#include "base/mat4.h"
#include "frame/frame_view.h"
#include "image/image.h"
#include "present/present.h"

#define GAMMA 2.2f

static char dir[64];

/* Presents one frame of the given viewports (their sources filled by fill(vp, rgb)) as PNG
 * and returns viewport `want`'s file (free() it). */
static uint8_t *present_once(const present_viewport *vps, int n, void (*fill)(int, uint8_t *, int, int),
                             const float *view, int show_blend, int want, int *w, int *h)
{
    char err[512] = "";
    present_desc d = {.output = PRESENT_PNG, .backend = GLCTX_EGL, .fallback = 1, .log_name = "test_present",
                      .viewport_count = n, .viewports = vps, .out_dir = dir};
    present *p = present_create(&d, err, sizeof err);
    if (!p)
        fail_msg("%s", err);
    for (int i = 0; i < n; i++) {
        fill(i, present_source(p, i), vps[i].width, vps[i].height);
        if (view)
            present_set_view(p, i, view);
    }
    present_frame_desc f = {.version = 1, .display_gamma = GAMMA, .show_blend = show_blend};
    if (present_frame(p, &f, err, sizeof err) != 0)
        fail_msg("%s", err);
    present_destroy(p);
    char path[256];
    snprintf(path, sizeof path, "%s/%s.png", dir, vps[want].name);
    uint8_t *rgb = NULL;
    if (image_read_png(path, w, h, &rgb, err, sizeof err) != 0)
        fail_msg("%s", err);
    return rgb;
}

static double light(uint8_t v)
{
    return pow(v / 255.0, GAMMA);
}

/* ---- as rendered ---------------------------------------------------------------------- */

static void fill_noise(int vp, uint8_t *rgb, int w, int h)
{
    for (int i = 0; i < w * h * 3; i++)
        rgb[i] = (uint8_t)((i * 2654435761u + (unsigned)vp * 97u) >> 13);
}

static void test_as_rendered(void **state)
{
    (void)state;
    present_viewport vp = {.name = "plain", .width = 37, .height = 23};
    int w, h;
    uint8_t *out = present_once(&vp, 1, fill_noise, NULL, 0, 0, &w, &h);
    uint8_t *want = malloc(37 * 23 * 3);
    fill_noise(0, want, 37, 23);
    assert_int_equal(w, 37);
    assert_int_equal(h, 23);
    assert_memory_equal(out, want, 37 * 23 * 3);
    free(out);
    free(want);
}

/* ---- two blended projectors ------------------------------------------------------------- */

enum { WALL_W = 64, PROJ_W = 40, OVERLAP = 16, WALL_H = 12 };

/* The wall's unblended image: smooth, every level from dark to bright, colours apart. */
static uint8_t wall(int x, int y, int c)
{
    return (uint8_t)(20 + (x * 3 + y * 5 + c * 40) % 220);
}

/* Projector 0 shows wall columns 0..39, projector 1 columns 24..63. */
static void fill_wall(int vp, uint8_t *rgb, int w, int h)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                rgb[(y * w + x) * 3 + c] = wall(x + vp * (WALL_W - PROJ_W), y, c);
}

static float smooth(float t)
{
    return t * t * (3 - 2 * t);
}

/* Stored with gamma 2.2 embedded (as most files are): value = alpha^(1/2.2). */
static void ramp_map(warp_map *m, int right)
{
    memset(m, 0, sizeof *m);
    m->place[0] = -1;
    m->alpha_gamma = GAMMA;
    m->alpha = (warp_blend_map){.width = PROJ_W, .height = 2, .channels = 1, .values = calloc(PROJ_W * 2, sizeof(float))};
    for (int x = 0; x < PROJ_W; x++) {
        int k = right ? x : x - (PROJ_W - OVERLAP); /* the overlap column */
        float a = k < 0 ? (right ? 0 : 1) : k >= OVERLAP ? (right ? 1 : 0) : smooth((k + 0.5f) / OVERLAP);
        a = right ? a : (k < 0 ? 1 : 1 - a);
        m->alpha.values[x] = m->alpha.values[PROJ_W + x] = powf(a, 1 / GAMMA);
    }
}

static void test_blend_sum(void **state)
{
    (void)state;
    warp_map maps[2];
    ramp_map(&maps[0], 0);
    ramp_map(&maps[1], 1);
    present_viewport vps[2] = {{.name = "p0", .width = PROJ_W, .height = WALL_H, .warp = &maps[0]},
                               {.name = "p1", .width = PROJ_W, .height = WALL_H, .warp = &maps[1]}};
    int w, h;
    uint8_t *a = present_once(vps, 2, fill_wall, NULL, 0, 0, &w, &h);
    uint8_t *b = present_once(vps, 2, fill_wall, NULL, 0, 1, &w, &h);
    double worst = 0;
    for (int y = 0; y < WALL_H; y++)
        for (int x = 0; x < WALL_W; x++)
            for (int c = 0; c < 3; c++) {
                int xa = x, xb = x - (WALL_W - PROJ_W);
                double sum = (xa < PROJ_W ? light(a[(y * PROJ_W + xa) * 3 + c]) : 0) +
                             (xb >= 0 ? light(b[(y * PROJ_W + xb) * 3 + c]) : 0);
                double err = fabs(sum - light(wall(x, y, c)));
                worst = err > worst ? err : worst;
                if (xb < 0) /* only projector 0 there: as rendered */
                    assert_int_equal(a[(y * PROJ_W + xa) * 3 + c], wall(x, y, c));
            }
    /* Two 8-bit roundings of up to half a step each: at most 2 x 0.5 x 2.2 / 255 of light. */
    printf("blend: worst |sum - unblended| %.4f of full light in the overlap\n", worst);
    assert_true(worst < 0.0087);
    free(a);
    free(b);
    warp_map_free(&maps[0]);
    warp_map_free(&maps[1]);
}

/* ---- known warps -------------------------------------------------------------------------- */

enum { SRC_W = 64, SRC_H = 48 };

/* R and G hold the texel centre's (u, v), so that a sample's colour says where it came from. */
static void fill_uv(int vp, uint8_t *rgb, int w, int h)
{
    (void)vp;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t *p = rgb + (y * w + x) * 3;
            p[0] = (uint8_t)lround(255.0 * (x + 0.5) / w);
            p[1] = (uint8_t)lround(255.0 * (h - y - 0.5) / h); /* v up, the image's top row first */
            p[2] = 0;
        }
}

/* The source point an output pixel shows, read from its colour. */
static void shown(const uint8_t *out, int w, int x, int y, double *u, double *v)
{
    *u = out[(y * w + x) * 3] / 255.0;
    *v = out[(y * w + x) * 3 + 1] / 255.0;
}

/* Output pixel centre (x, y from the top) in the projector image's coordinates (from the bottom). */
static void centre(int x, int y, int w, int h, double *px, double *py)
{
    *px = (x + 0.5) / w;
    *py = (h - y - 0.5) / h;
}

static void check_near(double got, double want, double tol, const char *what, int x, int y)
{
    if (fabs(got - want) > tol)
        fail_msg("%s at pixel (%d, %d): %.4f, the closed form says %.4f", what, x, y, got, want);
}

/* u = 0.25 + 0.5 x, v = 0.9 - 0.8 y on a 5 x 4 grid: exact everywhere, edges too. */
static void test_uv_grid(void **state)
{
    (void)state;
    warp_map m = {.kind = WARP_UV_GRID, .out_w = 50, .out_h = 30, .place = {-1, -1}, .grid_w = 5, .grid_h = 4,
                  .alpha_gamma = 1};
    m.grid = calloc(5 * 4 * 3, sizeof(float));
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 5; i++) {
            m.grid[(j * 5 + i) * 3] = 0.25f + 0.5f * (i + 0.5f) / 5;
            m.grid[(j * 5 + i) * 3 + 1] = 0.9f - 0.8f * (j + 0.5f) / 4;
        }
    present_viewport vp = {.name = "uv", .width = SRC_W, .height = SRC_H, .warp = &m};
    int w, h;
    uint8_t *out = present_once(&vp, 1, fill_uv, NULL, 0, 0, &w, &h);
    assert_int_equal(w, 50); /* the projector image is the map's size */
    assert_int_equal(h, 30);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double px, py, u, v;
            centre(x, y, w, h, &px, &py);
            shown(out, w, x, y, &u, &v);
            /* Bilinear sampling of a linear ramp is the ramp: 1.5/255 covers the 8-bit steps. */
            check_near(u, 0.25 + 0.5 * px, 1.5 / 255, "u", x, y);
            check_near(v, 0.9 - 0.8 * py, 1.5 / 255, "v", x, y);
        }
    free(out);
    warp_map_free(&m);
}

/* A keystone mesh: the top edge pulled in to 0.1..0.9. Its two triangles (present_warp.c:
 * (0, 1, 3) and (0, 3, 2)) each map affinely; solving them gives v = y and
 * u = x + 0.1 y right of the diagonal x = 0.9 y, u = (x - 0.1 y) / 0.8 left of it. */
static void test_mesh_keystone(void **state)
{
    (void)state;
    static const float v[4][5] = {{0, 0, 0, 0, 1}, {1, 0, 1, 0, 1}, {0.1f, 1, 0, 1, 1}, {0.9f, 1, 1, 1, 1}};
    warp_map m = {.kind = WARP_MESH, .place = {-1, -1}, .mesh_cols = 2, .mesh_rows = 2, .alpha_gamma = 1};
    m.mesh = malloc(sizeof v);
    memcpy(m.mesh, v, sizeof v);
    present_viewport vp = {.name = "mesh", .width = SRC_W, .height = SRC_H, .warp = &m};
    int w, h, inside = 0, outside = 0;
    uint8_t *out = present_once(&vp, 1, fill_uv, NULL, 0, 0, &w, &h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double px, py, u, vv;
            centre(x, y, w, h, &px, &py);
            shown(out, w, x, y, &u, &vv);
            double left = 0.1 * py, right = 1 - 0.1 * py, margin = 1.0 / w;
            if (px < left - margin || px > right + margin) { /* no cell there: black */
                assert_true(out[(y * w + x) * 3] == 0 && out[(y * w + x) * 3 + 1] == 0);
                outside++;
                continue;
            }
            if (px < left + margin || px > right - margin || fabs(px - 0.9 * py) < margin)
                continue; /* edges: either side's rule */
            double eu = px >= 0.9 * py ? px + 0.1 * py : (px - 0.1 * py) / 0.8;
            check_near(u, eu, 1.5 / 255, "u", x, y);
            check_near(vv, py, 1.5 / 255, "v", x, y);
            inside++;
        }
    assert_true(inside > w * h / 2);
    assert_true(outside > w * h / 40); /* the corners the keystone leaves */
    free(out);
    warp_map_free(&m);
}

/* A 3d grid: each projector pixel lights the point P = (-1.2 + 2.4 x, 0.1 + 1.2 y,
 * -2.5 + 0.5 y) of a tilted surface; the screen is z = -2, x -1..1, y 0..1.5 and the eye
 * sits at E = (0.2, 0.7, 0). The pixel must show where the ray from E through P meets the
 * screen: u = (hx + 1) / 2, v = hy / 1.5. */
static void surface_point(double px, double py, double p[3])
{
    p[0] = -1.2 + 2.4 * px;
    p[1] = 0.1 + 1.2 * py;
    p[2] = -2.5 + 0.5 * py;
}

static void test_point_grid(void **state)
{
    (void)state;
    warp_map m = {.kind = WARP_POINT_GRID, .out_w = 48, .out_h = 36, .place = {-1, -1}, .grid_w = 3, .grid_h = 3,
                  .alpha_gamma = 1};
    m.grid = calloc(3 * 3 * 3, sizeof(float));
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            double p[3];
            surface_point((i + 0.5) / 3, (j + 0.5) / 3, p);
            for (int k = 0; k < 3; k++)
                m.grid[(j * 3 + i) * 3 + k] = (float)p[k];
        }
    const float bl[3] = {-1, 0, -2}, br[3] = {1, 0, -2}, tl[3] = {-1, 1.5f, -2}, eye[3] = {0.2f, 0.7f, 0};
    frame_view fv;
    assert_int_equal(frame_view_screen(bl, br, tl, eye, 50, SRC_W, SRC_H, &fv, NULL), 0);
    float cave_to_clip[16];
    mat4_mul(fv.projection, fv.view, cave_to_clip);
    present_viewport vp = {.name = "points", .width = SRC_W, .height = SRC_H, .warp = &m};
    int w, h, checked = 0;
    uint8_t *out = present_once(&vp, 1, fill_uv, cave_to_clip, 0, 0, &w, &h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double px, py, p[3], u, v;
            centre(x, y, w, h, &px, &py);
            surface_point(px, py, p);
            double t = (-2 - eye[2]) / (p[2] - eye[2]);
            double eu = (eye[0] + t * (p[0] - eye[0]) + 1) / 2, ev = (eye[1] + t * (p[1] - eye[1])) / 1.5;
            if (eu < 0.01 || eu > 0.99 || ev < 0.01 || ev > 0.99)
                continue; /* off the screen's image, or at its edge */
            shown(out, w, x, y, &u, &v);
            check_near(u, eu, 2.0 / 255, "u", x, y);
            check_near(v, ev, 2.0 / 255, "v", x, y);
            checked++;
        }
    assert_true(checked > w * h / 2);
    free(out);
    warp_map_free(&m);
}

/* ---- beta, per-channel alpha, the blend-regions variant ----------------------------------- */

static void fill_grey(int vp, uint8_t *rgb, int w, int h)
{
    memset(rgb, vp == 0 ? 0 : 128, (size_t)w * h * 3);
}

static void test_beta_and_channels(void **state)
{
    (void)state;
    float beta[4] = {0.1f, 0.1f, 0.1f, 0.1f}, alpha[12];
    for (int i = 0; i < 4; i++) {
        alpha[3 * i] = 1;
        alpha[3 * i + 1] = 0.5f;
        alpha[3 * i + 2] = 0.25f;
    }
    warp_map lifted = {.place = {-1, -1}, .alpha_gamma = 1,
                       .beta = {.width = 2, .height = 2, .channels = 1, .values = beta}};
    warp_map tinted = {.place = {-1, -1}, .alpha_gamma = 1,
                       .alpha = {.width = 2, .height = 2, .channels = 3, .values = alpha}};
    present_viewport vps[2] = {{.name = "black", .width = 8, .height = 8, .warp = &lifted},
                               {.name = "grey", .width = 8, .height = 8, .warp = &tinted}};
    int w, h;
    uint8_t *a = present_once(vps, 2, fill_grey, NULL, 0, 0, &w, &h);
    uint8_t *b = present_once(vps, 2, fill_grey, NULL, 0, 1, &w, &h);
    /* Black lifted to beta's light; grey dimmed per channel by alpha (in light, not in code values). */
    for (int c = 0; c < 3; c++) {
        assert_int_equal(a[c], (int)lround(255 * pow(0.1, 1 / GAMMA)));
        assert_int_equal(b[c], (int)lround(255 * pow(light(128) * alpha[c], 1 / GAMMA)));
    }
    free(a);
    free(b);
}

static void test_show_blend(void **state)
{
    (void)state;
    warp_map m;
    ramp_map(&m, 0);
    present_viewport vp = {.name = "regions", .width = PROJ_W, .height = WALL_H, .warp = &m};
    int w, h;
    uint8_t *out = present_once(&vp, 1, fill_wall, NULL, 1, 0, &w, &h);
    for (int y = 0; y < WALL_H; y++)
        for (int x = 0; x < PROJ_W; x++) {
            const uint8_t *o = out + (y * PROJ_W + x) * 3;
            int diff = 0;
            for (int c = 0; c < 3; c++)
                diff += abs(o[c] - wall(x, y, c));
            if (x < PROJ_W - OVERLAP) /* full weight: the pattern as drawn */
                assert_int_equal(diff, 0);
            else /* dimmed here: tinted, so a person sees the region */
                assert_true(diff > 40);
        }
    free(out);
    warp_map_free(&m);
}

/* ---- window output -------------------------------------------------------------------------- */

static const uint8_t EYE_COLOUR[2][3] = {{200, 60, 20}, {30, 120, 240}};

static void fill_eye(int vp, uint8_t *rgb, int w, int h)
{
    for (int i = 0; i < w * h; i++)
        memcpy(rgb + 3 * i, EYE_COLOUR[vp], 3);
}

/* The colour a mode shows at window pixel (x, y from the top) of a W x H eye image. */
static void expected(cluster_stereo mode, int x, int y, int w, int h, uint8_t out[3])
{
    int eye = mode == CLUSTER_STEREO_TOP_BOTTOM ? y >= h : x >= w;
    if (mode == CLUSTER_STEREO_ANAGLYPH) {
        out[0] = EYE_COLOUR[0][0];
        out[1] = EYE_COLOUR[1][1];
        out[2] = EYE_COLOUR[1][2];
        return;
    }
    memcpy(out, EYE_COLOUR[eye], 3);
}

static void window_mode(cluster_stereo mode)
{
    enum { W = 12, H = 8 };
    present_viewport vps[2] = {{.name = "l", .width = W, .height = H, .eye = 0},
                               {.name = "r", .width = W, .height = H, .eye = 1}};
    cluster_window cw = {.monitor = {0, 1}};
    char err[512];
    present_desc d = {.output = PRESENT_WINDOW, .log_name = "test_present", .quiet = 1, .viewport_count = 2,
                      .viewports = vps, .stereo = mode, .window = &cw};
    present *p = present_create(&d, err, sizeof err);
    if (!p)
        fail_msg("stereo %s: %s", cluster_stereo_name(mode), err);
    for (int i = 0; i < 2; i++)
        fill_eye(i, present_source(p, i), W, H);
    present_frame_desc f = {.display_gamma = GAMMA};
    assert_int_equal(present_frame(p, &f, err, sizeof err), 0);
    int ww = mode == CLUSTER_STEREO_TOP_BOTTOM || mode == CLUSTER_STEREO_ANAGLYPH ? W : 2 * W;
    int wh = mode == CLUSTER_STEREO_TOP_BOTTOM ? 2 * H : H;
    uint8_t shown[2 * W * 2 * H * 3];
    const gl_functions *gl = glctx_gl(present_context(p));
    /* What was drawn before the swap (Mesa's X11 software path keeps the back buffer). */
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->ReadBuffer(GL_BACK_LEFT);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->ReadPixels(0, 0, ww, wh, GL_RGB, GL_UNSIGNED_BYTE, shown);
    for (int y = 0; y < wh; y++)
        for (int x = 0; x < ww; x++) {
            uint8_t want[3];
            expected(mode, x, y, W, H, want);
            const uint8_t *got = shown + ((size_t)(wh - 1 - y) * ww + x) * 3;
            if (memcmp(got, want, 3))
                fail_msg("stereo %s: window pixel (%d, %d) is %d %d %d, not %d %d %d", cluster_stereo_name(mode), x,
                         y, got[0], got[1], got[2], want[0], want[1], want[2]);
        }
    present_destroy(p);
}

static void test_window_stereo(void **state)
{
    (void)state;
    if (access("/usr/bin/Xvfb", X_OK) != 0) {
        printf("SKIP window part: /usr/bin/Xvfb not installed (apt-get install xvfb)\n");
        return;
    }
    /* Xvfb picks a free display and writes its number once it accepts clients; -noreset:
     * each mode's window is a new client, and a server resetting after the last one left
     * refuses the next for a moment. */
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    pid_t x = fork();
    if (x == 0) {
        prctl(PR_SET_PDEATHSIG, SIGTERM); /* a failed assertion must not leave it running */
        if (!freopen("/dev/null", "w", stderr) || dup2(fds[1], 3) != 3)
            _exit(127);
        unsetenv("LD_PRELOAD"); /* a sanitized run preloads its runtime for us, not for Xvfb */
        execl("/usr/bin/Xvfb", "Xvfb", "-displayfd", "3", "-noreset", "-screen", "0", "640x480x24", "-nolisten", "tcp",
              (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    /* Read to the newline: closing the pipe before Xvfb has written it all would end it. */
    char number[16] = "", name[20];
    size_t got = 0;
    struct pollfd pfd = {.fd = fds[0], .events = POLLIN};
    while (got < sizeof number - 1 && !strchr(number, '\n') && poll(&pfd, 1, 20000) == 1) {
        ssize_t n = read(fds[0], number + got, sizeof number - 1 - got);
        if (n <= 0)
            break;
        got += (size_t)n;
        number[got] = 0;
    }
    close(fds[0]);
    assert_non_null(strchr(number, '\n'));
    snprintf(name, sizeof name, ":%d", atoi(number));
    setenv("DISPLAY", name, 1);
    static const cluster_stereo modes[] = {CLUSTER_STEREO_SIDE_BY_SIDE, CLUSTER_STEREO_TOP_BOTTOM,
                                           CLUSTER_STEREO_ANAGLYPH, CLUSTER_STEREO_QUAD};
    for (size_t i = 0; i < sizeof modes / sizeof *modes; i++)
        window_mode(modes[i]); /* quad: llvmpipe has no quad buffers, so side-by-side */
    unsetenv("DISPLAY");
    kill(x, SIGTERM);
    waitpid(x, NULL, 0);
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/cavelight-present-XXXXXX");
    if (!mkdtemp(dir))
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_as_rendered),  cmocka_unit_test(test_blend_sum),
        cmocka_unit_test(test_uv_grid),      cmocka_unit_test(test_mesh_keystone),
        cmocka_unit_test(test_point_grid),   cmocka_unit_test(test_beta_and_channels),
        cmocka_unit_test(test_show_blend),   cmocka_unit_test(test_window_stereo),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        return 1;
    return rc;
}
