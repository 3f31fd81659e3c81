/* Anti-aliasing on llvmpipe (renderer_aa.h). FXAA on a hard-stepped straight edge brings
 * the image closer to the edge's exact pixel coverage: its staircase energy (the squared
 * difference from the coverage image) drops below 30% (12% and 18% measured), for a
 * near-horizontal and a near-vertical edge; a pixel whose four neighbours equal it, and a
 * whole image of a gentle ramp (below FXAA's contrast threshold), come out bit for bit
 * unchanged. Through the renderer: `aa fxaa` changes the default room's picture only at
 * its edges. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "gl/gltools.h"
#include "renderer_aa.h"

enum { S = 96, SUPER = 16 };

/* The edge y = slope * x + offset (pixel units), white above; sub-pixel coverage. */
typedef struct edge {
    double slope, offset;
    int transpose;           /* swap x and y: a near-vertical edge */
} edge;

static int above(const edge *e, double x, double y)
{
    if (e->transpose) {
        double t = x;
        x = y;
        y = t;
    }
    return y > e->slope * x + e->offset;
}

static double coverage(const edge *e, int px, int py)
{
    int in = 0;
    for (int j = 0; j < SUPER; j++)
        for (int i = 0; i < SUPER; i++)
            in += above(e, px + (i + 0.5) / SUPER, py + (j + 0.5) / SUPER);
    return (double)in / (SUPER * SUPER);
}

/* The w x h RGBA image through renderer_aa's mode, as RGBA. */
static void apply(const gl_functions *gl, renderer_aa *aa, frame_aa mode, const uint8_t *in,
                  uint8_t *out)
{
    GLuint tex = gltools_texture2d(gl, GL_RGBA8, S, S, GL_NEAREST), vao;
    gl->BindTexture(GL_TEXTURE_2D, tex);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, in);
    gl->GenVertexArrays(1, &vao);
    GLuint fbo = renderer_aa_apply(aa, mode, tex, S, S, vao);
    assert_true(fbo != 0);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->ReadPixels(0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, out);
    assert_int_equal(gl->GetError(), GL_NO_ERROR);
    gl->DeleteVertexArrays(1, &vao);
    gl->DeleteTextures(1, &tex);
}

static void open_aa(glctx **ctx, renderer_aa **aa)
{
    char err[512];
    glctx_desc gd = {.backend = GLCTX_EGL};
    *ctx = glctx_create(&gd, err, sizeof err);
    if (!*ctx)
        fail_msg("%s", err);
    *aa = renderer_aa_create(glctx_gl(*ctx), err, sizeof err);
    if (!*aa)
        fail_msg("%s", err);
}

/* Pixels whose value differs from one of their four neighbours': where an edge is. */
static int on_edge(const uint8_t *img, int x, int y)
{
    const int d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int k = 0; k < 4; k++) {
        int nx = x + d[k][0], ny = y + d[k][1];
        if (nx >= 0 && ny >= 0 && nx < S && ny < S &&
            memcmp(img + ((size_t)ny * S + nx) * 4, img + ((size_t)y * S + x) * 4, 3) != 0)
            return 1;
    }
    return 0;
}

static void check_edge(const edge *e)
{
    glctx *ctx;
    renderer_aa *aa;
    open_aa(&ctx, &aa);
    uint8_t *in = malloc((size_t)S * S * 4), *out = malloc((size_t)S * S * 4);
    double *cover = malloc((size_t)S * S * sizeof *cover);
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            size_t i = (size_t)y * S + x;
            cover[i] = coverage(e, x, y);
            uint8_t v = above(e, x + 0.5, y + 0.5) ? 255 : 0;
            in[4 * i] = in[4 * i + 1] = in[4 * i + 2] = v;
            in[4 * i + 3] = 255;
        }
    apply(glctx_gl(ctx), aa, FRAME_AA_FXAA, in, out);
    double before = 0, after = 0;
    size_t changed_flat = 0;
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            size_t i = (size_t)y * S + x;
            double a = in[4 * i] / 255.0 - cover[i], b = out[4 * i] / 255.0 - cover[i];
            before += a * a;
            after += b * b;
            changed_flat += !on_edge(in, x, y) && memcmp(in + 4 * i, out + 4 * i, 4) != 0;
        }
    printf("slope %.3f%s: staircase energy %.2f -> %.2f (%.0f%%), flat pixels changed %zu\n",
           e->slope, e->transpose ? " (transposed)" : "", before, after, 100.0 * after / before,
           changed_flat);
    assert_true(after < 0.3 * before);
    assert_int_equal(changed_flat, 0);
    free(in);
    free(out);
    free(cover);
    renderer_aa_destroy(aa);
    glctx_destroy(ctx);
}

static void test_near_horizontal_edge(void **state)
{
    (void)state;
    check_edge(&(edge){.slope = 0.2, .offset = 38.3});
}

static void test_near_vertical_edge(void **state)
{
    (void)state;
    check_edge(&(edge){.slope = 0.3, .offset = 30.7, .transpose = 1});
}

/* A ramp of 7 levels a pixel (a pixel's neighbours span 14 levels, under FXAA's least
 * contrast of 16) in grey, flat beyond, and a third of a level a pixel down the image in green:
 * no edge for FXAA, every byte kept. */
static void test_gentle_ramp_unchanged(void **state)
{
    (void)state;
    glctx *ctx;
    renderer_aa *aa;
    open_aa(&ctx, &aa);
    uint8_t *in = malloc((size_t)S * S * 4), *out = malloc((size_t)S * S * 4);
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            uint8_t *p = in + ((size_t)y * S + x) * 4;
            int v = 60 + 7 * (x < 27 ? x : 27);
            p[0] = (uint8_t)v;
            p[1] = (uint8_t)(v - 40 + y / 3);
            p[2] = (uint8_t)v;
            p[3] = 255;
        }
    apply(glctx_gl(ctx), aa, FRAME_AA_FXAA, in, out);
    assert_memory_equal(in, out, (size_t)S * S * 4);
    free(in);
    free(out);
    renderer_aa_destroy(aa);
    glctx_destroy(ctx);
}

/* The default room with `aa fxaa` against `aa off`: the same picture where it is flat,
 * softer where it has edges. */
static void test_renderer_setting(void **state)
{
    (void)state;
    enum { W = 128, H = 96 };
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    renderer_view v;
    gltest_look_at(&v, t.scene.camera.position, t.scene.camera.target, t.scene.camera.yfov, W, H);
    uint8_t *img[2];
    for (int k = 0; k < 2; k++) {
        frame_params p = t.params;
        gltest_setn(&p, "lambda", 0); /* every frame's light the same */
        gltest_set(&p, "aa", k ? "fxaa" : "off");
        renderer_image out;
        renderer_frame_pass(t.r, &p);
        assert_int_equal(renderer_eye_pass(t.r, &v, 0, &out), 0);
        img[k] = malloc((size_t)W * H * 3);
        memcpy(img[k], out.rgb, (size_t)W * H * 3);
    }
    size_t changed = 0, changed_flat = 0;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            const uint8_t *a = img[0] + ((size_t)y * W + x) * 3;
            int flat = 1;
            for (int d = -1; d <= 1; d += 2)
                flat &= !memcmp(a, a + 3 * d, 3) && !memcmp(a, a + (ptrdiff_t)3 * W * d, 3);
            int differs = memcmp(a, img[1] + ((size_t)y * W + x) * 3, 3) != 0;
            changed += differs;
            changed_flat += differs && flat;
        }
    printf("aa fxaa: %zu pixels changed, %zu of them flat\n", changed, changed_flat);
    assert_true(changed > 0);
    assert_int_equal(changed_flat, 0);
    free(img[0]);
    free(img[1]);
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_near_horizontal_edge),
        cmocka_unit_test(test_near_vertical_edge),
        cmocka_unit_test(test_gentle_ramp_unchanged),
        cmocka_unit_test(test_renderer_setting),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
