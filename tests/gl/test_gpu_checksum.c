/* READY's checksum of what stays on the GPU (node/gl/gpu_checksum.h) on llvmpipe: the value
 * is the host's formula over the records' words, arrives at the next frame (one frame
 * late), stays while frames submit nothing, and changes with one word. Two renderers of the
 * caches method (two nodes; the method's result lives on the GPU only) agree frame by
 * frame, and a difference in one of them (its caches-seed in one frame) shows in the
 * checksum of the frame after: what the master's desync rule sees (docs/cluster.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <unistd.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "gl/gpu_checksum.h"

enum { RECORDS = 700, STRIDE = 6, WIDTH = 4 };

static uint32_t mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* shaders/checksum.comp's sums on the host: the first WIDTH words of each record. */
static uint64_t host_sum(const uint32_t *words, int salt)
{
    uint32_t s0 = 0, s1 = 0;
    for (uint32_t i = 0; i < RECORDS * WIDTH; i++) {
        uint32_t a = mix32(words[(i / WIDTH) * STRIDE + i % WIDTH] ^ mix32(i + (uint32_t)salt * 0x9e3779b9u));
        s0 += a;
        s1 += mix32(a ^ 0x85ebca6bu);
    }
    return (uint64_t)s0 | (uint64_t)s1 << 32;
}

static void test_late_exact_and_kept(void **state)
{
    (void)state;
    char err[256];
    glctx_desc gd = {.backend = GLCTX_EGL};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    assert_non_null(ctx);
    const gl_functions *gl = glctx_gl(ctx);
    gpu_checksum *c = gpu_checksum_create(gl, err, sizeof err);
    assert_non_null(c);
    static uint32_t words[RECORDS * STRIDE];
    for (size_t i = 0; i < RECORDS * STRIDE; i++)
        words[i] = mix32((uint32_t)i * 2654435761u);
    GLuint buf;
    gl->GenBuffers(1, &buf);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    gl->BufferData(GL_SHADER_STORAGE_BUFFER, sizeof words, words, GL_DYNAMIC_DRAW);

    assert_int_equal(gpu_checksum_frame(c), 0); /* nothing submitted yet */
    gpu_checksum_add(c, buf, 0, RECORDS, WIDTH, STRIDE);
    gpu_checksum_submit(c);
    uint64_t first = gpu_checksum_frame(c);
    assert_true(first == host_sum(words, 0));
    gpu_checksum_submit(c); /* a frame with no parts: 0 next */
    assert_true(gpu_checksum_frame(c) == 0);
    gpu_checksum_add(c, buf, 0, RECORDS, WIDTH, STRIDE);
    gpu_checksum_submit(c);
    assert_true(gpu_checksum_frame(c) == first);
    assert_true(gpu_checksum_frame(c) == first); /* submitted nothing (reused): kept */

    words[3 * STRIDE + 1] ^= 1; /* one bit of one counted word */
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    gl->BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof words, words);
    gpu_checksum_add(c, buf, 0, RECORDS, WIDTH, STRIDE);
    gpu_checksum_submit(c);
    uint64_t changed = gpu_checksum_frame(c);
    assert_true(changed != first && changed == host_sum(words, 0));

    words[3 * STRIDE + 5] ^= 1; /* a word outside the records' width: not counted */
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    gl->BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof words, words);
    gpu_checksum_add(c, buf, 0, RECORDS, WIDTH, STRIDE);
    gpu_checksum_submit(c);
    assert_true(gpu_checksum_frame(c) == changed);
    gl->DeleteBuffers(1, &buf);
    gpu_checksum_destroy(c);
    glctx_destroy(ctx);
}

static char cache_dir[256];

static renderer *caches_renderer(glctx *ctx, const scene *s, const frame_params *p)
{
    char err[256];
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = s, .first = p};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r)
        fprintf(stderr, "%s\n", err);
    return r;
}

static uint64_t run_frame(renderer *r, const frame_params *p, const renderer_view *v)
{
    uint64_t sum = renderer_frame_pass(r, p);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(r, v, 0, &img), 0);
    return sum;
}

static void test_nodes_agree_and_a_difference_shows_late(void **state)
{
    (void)state;
    snprintf(cache_dir, sizeof cache_dir, "%s/test_gpu_checksum.%ld", CAVELIGHT_BINARY_DIR,
             (long)getpid());
    setenv("CAVELIGHT_CACHE_DIR", cache_dir, 1);
    char err[256];
    glctx_desc gd = {.backend = GLCTX_EGL};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    assert_non_null(ctx);
    scene s;
    assert_int_equal(scene_load("default", &s, err, sizeof err), 0);
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, &s);
    p.gi = gi_method_find("caches");
    gltest_setn(&p, "rsm", 32);
    gltest_setn(&p, "caches-vals", 256);
    renderer *a = caches_renderer(ctx, &s, &p), *b = caches_renderer(ctx, &s, &p);
    assert_non_null(a);
    assert_non_null(b);
    renderer_view v;
    const float eye[3] = {1.3f, 1.6f, 1.9f}, target[3] = {-0.5f, 0.9f, -1.2f};
    gltest_look_at(&v, eye, target, 1.15f, 32, 24);
    uint64_t sa[4], sb[4];
    for (int f = 0; f < 4; f++) {
        p.version = (uint64_t)f;
        p.lights[0].position[0] += 0.01f; /* every frame computed */
        frame_params q = p;
        if (f == 1)
            gltest_setn(&q, "caches-seed", 7); /* node b differs in frame 1 only */
        sa[f] = run_frame(a, &p, &v);
        sb[f] = run_frame(b, &q, &v);
    }
    assert_true(sa[0] == sb[0] && sa[1] == sb[1]); /* frame 1's difference not in yet */
    assert_true(sa[2] != sb[2]);                   /* ... it is in frame 2's */
    assert_true(sa[3] == sb[3]);                   /* and gone again */
    assert_true(sa[1] != sa[2] && sa[2] != sa[3]); /* the checksum follows the light */
    renderer_destroy(a);
    renderer_destroy(b);
    scene_free(&s);
    glctx_destroy(ctx);
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cache_dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_late_exact_and_kept),
        cmocka_unit_test(test_nodes_agree_and_a_difference_shows_late),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
