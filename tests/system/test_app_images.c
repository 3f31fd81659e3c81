/* The examples on a 2-node local cluster (real cavelight-node processes on GL, the master's
 * session here), their images checked:
 *   move:   the tall box where examples/move.c puts it at the last frame's time, on every
 *           node: each node's image equals this process's render of the same frame with the
 *           box there (the direct light only, so no history differs), and differs from the
 *           render with the box where it was loaded;
 *   grab:   a recorded wand picks the tall box with C and carries it 0.4 m to the left:
 *           the store holds that offset, and the box's faces show blue where it went;
 *   replay: the grab session's recording, replayed, gives every frame's image of every
 *           node again byte for byte (the ILPV's light and its history included). */
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cmocka.h>

#include "base/mat4.h"
#include "base/textfile.h"
#include "cluster_view.h"
#include "gi/gi_settings.h"
#include "gl/glctx.h"
#include "image/image.h"
#include "renderer.h"
#include "scene/scene_load.h"
#include "session.h"

#define DIR CAVELIGHT_BINARY_DIR "/test_app_images.d"
#define NODE_EXE CAVELIGHT_BINARY_DIR "/cavelight-node"
enum { W = 48, H = 64, NODES = 2 };

static const char *node_names[NODES] = {"a", "b"};
/* The node processes of the running session: a failed check leaves none behind. */
static pid_t running[NODES];

static void stop_nodes(void)
{
    for (int i = 0; i < NODES; i++)
        if (running[i] > 0) {
            kill(running[i], SIGTERM);
            waitpid(running[i], NULL, 0);
            running[i] = 0;
        }
}

static int teardown(void **state)
{
    (void)state;
    stop_nodes();
    return 0;
}

/* DIR/NAME/c.json: two nodes, front-left and front-right half walls of a 3 m CAVE, mono. */
static void write_config(const char *name, const char *settings, char *path, size_t n, cluster_config *cfg)
{
    char dir[400], json[4096], err[512];
    snprintf(dir, sizeof dir, DIR "/%s", name);
    mkdir(DIR, 0755);
    mkdir(dir, 0755);
    snprintf(path, n, "%s/c.json", dir);
    snprintf(json, sizeof json,
             "{\"master\": {\"bind\": \"tcp://127.0.0.1:*\", \"connect\": \"tcp://127.0.0.1:1\"},"
             " \"security\": {\"mode\": \"insecure\"},"
             " \"timeouts\": {\"barrier_ms\": 60000, \"heartbeat_ms\": 100, \"master_ms\": 60000},"
             " \"observer\": {\"home\": [0, 1.7, 0]}, \"settings\": {%s},"
             " \"screens\": [{\"name\": \"front-l\", \"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [0,0,-1.5],"
             " \"top_left\": [-1.5,3,-1.5]}, {\"name\": \"front-r\", \"bottom_left\": [0,0,-1.5],"
             " \"bottom_right\": [1.5,0,-1.5], \"top_left\": [0,3,-1.5]}],"
             " \"nodes\": [{\"name\": \"a\", \"screens\": [\"front-l\"], \"resolution\": [%d, %d], \"output\": \"png\"},"
             " {\"name\": \"b\", \"screens\": [\"front-r\"], \"resolution\": [%d, %d], \"output\": \"png\"}]}",
             settings, W, H, W, H);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(json, f);
    fclose(f);
    assert_int_equal(cluster_config_load(path, cfg, err, sizeof err), 0);
}

typedef struct run {
    const char *app, *input, *record, *out;
    int keep_frames;
    double dt;
    frame_params last;          /* the last frame as the master committed it */
    float box_offset[16];       /* tall_box's offset in it */
    int frames;
} run;

/* The master's session here, the nodes as processes; until the recording ends or frames. */
static void run_session(const char *config_path, const cluster_config *cfg, run *r, int frames)
{
    char err[512], endpoint[256];
    static frame_params settings; /* the config's "settings", as cavelight-master takes them */
    frame_params_default(&settings);
    assert_int_equal(gi_set_config(cfg, &settings, err, sizeof err), 0);
    session_desc sd = {.config = cfg, .quiet = 1, .dt = r->dt, .app = r->app, .input = r->input,
                       .record = r->record, .out_dir = r->out, .settings = &settings};
    session *s = session_create(&sd, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    assert_int_equal(cluster_master_endpoint(session_master(s), endpoint, sizeof endpoint), 0);
    pid_t pid[NODES];
    for (int i = 0; i < NODES; i++) {
        char *argv[] = {NODE_EXE, "--cluster", (char *)config_path, "--name", (char *)node_names[i], "--master",
                        endpoint, "--exit-with-master", "--app", (char *)r->app, "--out", (char *)r->out,
                        "--threads", "1", "--quiet", r->keep_frames ? "--keep-frames" : NULL, NULL};
        pid[i] = fork(); /* master/spawn.h's name hides <spawn.h> here */
        if (pid[i] == 0) {
            execv(NODE_EXE, argv);
            _exit(127);
        }
        assert_true(pid[i] > 0);
        running[i] = pid[i];
    }
    assert_int_equal(session_wait_nodes(s, NODES, 120000, NULL), NODES);
    r->frames = 0;
    for (int i = 0; i < frames; i++) {
        cluster_frame_result fr;
        session_step step = session_frame(s, &fr);
        if (step == SESSION_INPUT_ENDED)
            break;
        assert_int_equal(step, SESSION_FRAME_DONE);
        assert_int_equal(fr.ready, NODES); /* no frame lost */
        assert_int_equal(fr.desync, 0);    /* every node's checksum equal */
        r->frames++;
    }
    const params_store *st = cluster_master_params(session_master(s));
    params_to_frame(st, &r->last);
    assert_int_equal(params_get(st, params_schema_find(st->schema, "object.tall_box"), r->box_offset, 64), 0);
    session_destroy(s);
    for (int i = 0; i < NODES; i++) {
        int status;
        assert_int_equal(waitpid(pid[i], &status, 0), pid[i]);
        running[i] = 0;
        assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
}

/* This process's render of frame f with the tall box at offset, one node's screen. */
typedef struct local {
    glctx *ctx;
    scene sc;
    renderer *r;
    int box;
} local;

static void local_open(local *l, const cluster_config *cfg, const frame_params *f)
{
    char err[512];
    glctx_desc gd = {.backend = GLCTX_EGL};
    assert_non_null(l->ctx = glctx_create(&gd, err, sizeof err));
    scene_load_desc sd;
    cluster_config_scene_desc(cfg, &sd);
    assert_int_equal(scene_load_with("default", &sd, &l->sc, err, sizeof err), 0);
    renderer_desc rd = {.gl = glctx_gl(l->ctx), .scene = &l->sc, .first = f, .threads = 1};
    if (!(l->r = renderer_create(&rd, err, sizeof err)))
        fail_msg("%s", err);
    l->box = scene_object_find(&l->sc, "tall_box");
}

static void local_close(local *l)
{
    renderer_destroy(l->r);
    glctx_destroy(l->ctx);
    scene_free(&l->sc);
}

static void local_view(const local *l, const cluster_config *cfg, int node, const frame_params *f, renderer_view *v)
{
    assert_true(cluster_view_compute(cfg, cfg->nodes[node].screens[0].screen, 0, f, W, H, scene_far_plane(&l->sc), v,
                                     NULL) >= 0);
}

static const uint8_t *local_render(local *l, const cluster_config *cfg, int node, const frame_params *f,
                                   const float offset[16])
{
    scene_pose p;
    scene_pose_rest(&l->sc, &p);
    memcpy(p.offset[l->box], offset, 64);
    renderer_set_pose(l->r, &p);
    renderer_frame_pass(l->r, f);
    renderer_view v;
    local_view(l, cfg, node, f, &v);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(l->r, &v, 0, &img), 0);
    return img.rgb;
}

static int pixels_differing(const uint8_t *a, const uint8_t *b)
{
    int n = 0;
    for (int i = 0; i < W * H; i++)
        n += abs(a[3 * i] - b[3 * i]) > 2 || abs(a[3 * i + 1] - b[3 * i + 1]) > 2 || abs(a[3 * i + 2] - b[3 * i + 2]) > 2;
    return n;
}

static uint8_t *node_image(const char *out, int node, const char *screen)
{
    char path[600], err[300];
    snprintf(path, sizeof path, "%s/%s-mono.png", out, screen);
    int w, h;
    uint8_t *rgb = NULL;
    if (image_read_png(path, &w, &h, &rgb, err, sizeof err) != 0)
        fail_msg("node %s: %s", node_names[node], err);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    return rgb;
}

static void test_move(void **state)
{
    (void)state;
    static cluster_config cfg;
    char config[512];
    write_config("move", "\"gi\": \"none\", \"rsm\": 64", config, sizeof config, &cfg);
    run r = {.app = CAVELIGHT_BINARY_DIR "/examples/move.so", .out = DIR "/move", .dt = 0.5};
    run_session(config, &cfg, &r, 6);
    assert_int_equal(r.frames, 6);
    /* examples/move.c: offset (0.5 cos a - 0.5, 0, 0.5 sin a), a = 2 pi t / 8. */
    double a = 2.0 * 3.14159265358979 * r.last.time / 8.0;
    assert_true(r.last.time == 2.5);
    assert_true(fabsf(r.box_offset[12] - (float)(0.5 * cos(a) - 0.5)) < 1e-6f);
    assert_true(fabsf(r.box_offset[14] - (float)(0.5 * sin(a))) < 1e-6f);
    static local l;
    local_open(&l, &cfg, &r.last);
    const float rest[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int moved_pixels = 0;
    for (int n = 0; n < NODES; n++) {
        uint8_t *got = node_image(r.out, n, cfg.screens[cfg.nodes[n].screens[0].screen].name);
        int same = pixels_differing(got, local_render(&l, &cfg, n, &r.last, r.box_offset));
        int at_rest = pixels_differing(got, local_render(&l, &cfg, n, &r.last, rest));
        printf("move: node %s: %d pixels differ from the box where the app put it, %d from where it was "
               "loaded\n", node_names[n], same, at_rest);
        assert_true(same <= W * H / 200);
        moved_pixels += at_rest;
        free(got);
    }
    assert_true(moved_pixels > W * H / 20);
    local_close(&l);
}

/* The recording of a wand that points at the tall box (along -Z from x 0.85, y 0.8),
 * presses C, moves 0.4 m to the left while holding it, lets go and moves on. */
static void write_grab_session(const char *path)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "cavelight-input 1\n");
    for (int i = 0; i < 10; i++) {
        double t = 0.5 * i, x = 0.85 - 0.1 * (i < 2 ? 0 : i > 5 ? 4 + (i - 5) : i - 1);
        if (i == 0)
            fprintf(f, "head %.17g 0 1.7 0 1 0 0 0 1 0 0 0 1\n", t);
        fprintf(f, "wand %.17g %.9g 0.8 0.5 1 0 0 0 1 0 0 0 1\n", t, x);
        if (i == 1)
            fprintf(f, "buttons %.17g 8 8\n", t);
        if (i == 6)
            fprintf(f, "buttons %.17g 0 0\n", t);
        fprintf(f, "poll %.17g %.17g\n", t, i ? 0.5 : 0.0);
    }
    fclose(f);
}

static void test_grab_and_replay(void **state)
{
    (void)state;
    static cluster_config cfg;
    char config[512], session_txt[600], rec[600];
    write_config("grab", "\"lattice\": 16, \"rsm\": 64, \"exposure\": 6", config, sizeof config, &cfg);
    snprintf(session_txt, sizeof session_txt, DIR "/grab/session.txt");
    snprintf(rec, sizeof rec, DIR "/grab/recorded.txt");
    write_grab_session(session_txt);
    run first = {.app = CAVELIGHT_BINARY_DIR "/examples/grab.so", .input = session_txt, .record = rec,
                 .out = DIR "/grab/first", .keep_frames = 1};
    run_session(config, &cfg, &first, 100);
    assert_int_equal(first.frames, 10);
    /* Picked with the wand at x 0.85, held down to 0.45, let go: 0.4 m to the left. */
    assert_true(fabsf(first.box_offset[12] - -0.4f) < 1e-5f);
    assert_true(fabsf(first.box_offset[13]) < 1e-6f && fabsf(first.box_offset[14]) < 1e-6f);
    /* The box's top face, where it went, shows blue on node b's screen. */
    static local l;
    local_open(&l, &cfg, &first.last);
    renderer_view v;
    local_view(&l, &cfg, 1, &first.last, &v);
    uint8_t *got = node_image(first.out, 1, "front-r");
    int blue = 0, samples = 0;
    for (int i = 0; i < 5; i++)
        for (int k = 0; k < 5; k++) {
            float p[3] = {0.5f + 0.7f * (i + 0.5f) / 5 + first.box_offset[12], 1.6f, -1.4f + 0.7f * (k + 0.5f) / 5}, c[4];
            float vp[16];
            mat4_mul(v.projection, v.view, vp);
            for (int row = 0; row < 4; row++)
                c[row] = vp[row] * p[0] + vp[4 + row] * p[1] + vp[8 + row] * p[2] + vp[12 + row];
            int x = (int)((c[0] / c[3] * 0.5f + 0.5f) * W), y = (int)((0.5f - c[1] / c[3] * 0.5f) * H);
            if (x < 0 || y < 0 || x >= W || y >= H)
                continue;
            const uint8_t *q = got + 3 * (y * W + x);
            samples++;
            blue += q[2] > q[0] + 10 && q[2] > q[1];
        }
    printf("grab: %d of %d points of the moved box's top face on node b show blue\n", blue, samples);
    assert_true(samples >= 10 && blue >= samples * 8 / 10);
    free(got);
    local_close(&l);
    /* The replay: every frame of every node again, byte for byte. */
    run again = {.app = first.app, .input = rec, .out = DIR "/grab/replay", .keep_frames = 1};
    run_session(config, &cfg, &again, 100);
    assert_int_equal(again.frames, first.frames);
    int compared = 0;
    for (uint64_t ver = 1; ver <= (uint64_t)first.last.version; ver++)
        for (int n = 0; n < NODES; n++) {
            char a[700], b[700];
            const char *screen = cfg.screens[cfg.nodes[n].screens[0].screen].name;
            snprintf(a, sizeof a, "%s/%s-mono-%06llu.png", first.out, screen, (unsigned long long)ver);
            snprintf(b, sizeof b, "%s/%s-mono-%06llu.png", again.out, screen, (unsigned long long)ver);
            size_t la, lb;
            char err[300];
            char *da = textfile_read(a, &la, err, sizeof err), *db = textfile_read(b, &lb, err, sizeof err);
            if (!da && !db)
                continue;
            if (!da || !db || la != lb || memcmp(da, db, la) != 0)
                fail_msg("replay: %s and %s differ", a, b);
            compared++;
            free(da);
            free(db);
        }
    printf("replay: %d images of %d frames byte for byte equal\n", compared, first.frames);
    assert_true(compared >= NODES * first.frames);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_move, teardown),
        cmocka_unit_test_teardown(test_grab_and_replay, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
