/* cluster_config: the shipped configs load with the expected shape; broken configs fail
 * with one line naming the file and the field. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "cluster/cluster_config.h"

static cluster_config cfg;

static void load_shipped(const char *name)
{
    char path[512], err[512] = "";
    snprintf(path, sizeof path, "%s/configs/clusters/%s.json", CAVELIGHT_SOURCE_DIR, name);
    if (cluster_config_load(path, &cfg, err, sizeof err) != 0)
        fail_msg("%s", err);
}

static float dist(const float *a, const float *b)
{
    float d = 0;
    for (int i = 0; i < 3; i++)
        d += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrtf(d);
}

static void test_shipped_configs(void **state)
{
    static const char *const names[] = {"desktop", "desktop-local", "powerwall-2x2",
                                        "powerwall-2x2-local", "cave5", "cave5-local",
                                        "powerwall-blend-local"};
    static const int nodes[] = {1, 1, 4, 4, 10, 10, 2};
    for (int i = 0; i < 7; i++) {
        load_shipped(names[i]);
        assert_int_equal(cfg.node_count, nodes[i]);
        assert_int_equal(cfg.nodes[0].eyes, i < 2 ? CLUSTER_EYES_MONO : CLUSTER_EYES_STEREO);
        if (strstr(names[i], "-local"))
            assert_non_null(strstr(cfg.master_connect, "127.0.0.1"));
        else /* the defaults: nodes call a hung master lost well under a second */
            assert_true(cfg.master_timeout_ms > cfg.heartbeat_ms && cfg.master_timeout_ms < 1000);
        if (cfg.unknown_key_count) /* every key of a shipped config is read somewhere */
            fail_msg("%s", cfg.unknown_keys[0]);
    }
    /* The CAVE: 10 half walls of 1.5 x 3 m (walls) or 3 x 1.5 m (floor and ceiling). */
    load_shipped("cave5-local");
    assert_int_equal(cfg.screen_count, 10);
    for (int s = 0; s < 10; s++) {
        const cluster_screen *sc = &cfg.screens[s];
        float w = dist(sc->bottom_left, sc->bottom_right), h = dist(sc->bottom_left, sc->top_left);
        assert_float_equal(w * h, 4.5f, 1e-5);
        assert_int_equal(cfg.nodes[s].screens[0].screen, s);
        /* Pixels are square: resolution follows the screen's aspect. */
        assert_float_equal((float)cfg.nodes[s].screens[0].width / cfg.nodes[s].screens[0].height, w / h, 1e-3);
    }
    assert_float_equal(cfg.observer.eye_separation, 0.064f, 1e-6);
    assert_float_equal(cfg.observer.home[1], 1.7f, 1e-6);
    assert_float_equal(cfg.observer.tracker_to_cave[0], 1.0f, 1e-6);
    assert_int_equal(cluster_config_find_node(&cfg, "n10"), 9);
    assert_int_equal(cluster_config_find_node(&cfg, "n11"), -1);
}

static const char *good_head =
    "{\"master\": {\"bind\": \"tcp://*:5570\", \"connect\": \"tcp://h:5570\"},"
    " \"screens\": [{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [0,1,0]}],";

static void expect_error(const char *json, const char *field)
{
    char err[512] = "";
    int rc = cluster_config_parse(json, strlen(json), "bad.json", &cfg, err, sizeof err);
    if (rc == 0)
        fail_msg("accepted: %s", json);
    if (!strstr(err, "bad.json") || !strstr(err, field))
        fail_msg("error '%s' does not name the file and field '%s'", err, field);
    assert_null(strchr(err, '\n'));
}

static void test_bad_configs(void **state)
{
    char buf[2048];
    expect_error("{", "line 1");
    expect_error("[]", "top level");
    expect_error("{\"screens\": []}", "master");
    expect_error("{\"master\": {\"bind\": \"tcp://*:1\"}}", "master.connect");
    expect_error("{\"master\": {\"bind\": \"udp://x\", \"connect\": \"tcp://h:1\"}}", "master.bind");
#define NODES(x) (snprintf(buf, sizeof buf, "%s \"nodes\": [%s]}", good_head, x), buf)
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"nope\"], \"resolution\": [4,4]}"), "nodes[0].screens[0]");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"]}"), "nodes[0].screens[0]");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [0,4]}"), "nodes[0].resolution");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4], \"eyes\": \"three\"}"), "nodes[0].eyes");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4], \"output\": 3}"), "nodes[0].output");
    expect_error(NODES("{\"name\": \"a b\", \"screens\": [\"s\"], \"resolution\": [4,4]}"), "nodes[0].name");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4]},"
                       "{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4]}"), "nodes[1].name");
    expect_error(NODES(""), "nodes");
    snprintf(buf, sizeof buf, "%s \"observer\": {\"eye_separation\": 5}, \"nodes\": []}", good_head);
    expect_error(buf, "observer.eye_separation");
    snprintf(buf, sizeof buf, "%s \"timeouts\": {\"barrier_ms\": \"x\"}, \"nodes\": []}", good_head);
    expect_error(buf, "timeouts.barrier_ms");
    snprintf(buf, sizeof buf, "%s \"timeouts\": {\"heartbeat_ms\": 100, \"master_ms\": 150}, \"nodes\": []}", good_head);
    expect_error(buf, "timeouts.master_ms"); /* lost between two heartbeats */
    expect_error("{\"master\": {\"bind\": \"tcp://*:1\", \"connect\": \"tcp://h:1\"}, \"screens\": "
                 "[{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [1,1,0]}]}",
                 "screens[0]");
    expect_error("{\"master\": {\"bind\": \"tcp://*:1\", \"connect\": \"tcp://h:1\"}, \"screens\": "
                 "[{\"name\": \"s\", \"bottom_left\": [0,0], \"bottom_right\": [1,0,0], \"top_left\": [0,1,0]}]}",
                 "screens[0].bottom_left");

    /* A good minimal config, for contrast, with per-screen resolution. */
    char err[512] = "";
    const char *ok = NODES("{\"name\": \"a\", \"screens\": [{\"name\": \"s\", \"resolution\": [8, 6]}]}");
    assert_int_equal(cluster_config_parse(ok, strlen(ok), "ok.json", &cfg, err, sizeof err), 0);
    assert_int_equal(cfg.nodes[0].screens[0].width, 8);
    assert_int_equal(cfg.nodes[0].output, CLUSTER_OUTPUT_WINDOW);
    assert_int_equal(cfg.barrier_timeout_ms, 2000);
    assert_string_equal(cfg.nodes[0].host, "localhost");
    /* Where a node's program, folder and config lie on its host: the master's by default. */
    assert_string_equal(cfg.nodes[0].exe, "");
    assert_string_equal(cfg.nodes[0].workdir, "");
    assert_string_equal(cfg.nodes[0].config, "");
    assert_string_equal(cfg.nodes[0].display, ":0");
    const char *placed = NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4], "
                               "\"exe\": \"/opt/c/bin/node\", \"workdir\": \"/srv/cave\", "
                               "\"config\": \"cave.json\", \"display\": \":1\"}");
    assert_int_equal(cluster_config_parse(placed, strlen(placed), "ok.json", &cfg, err, sizeof err), 0);
    assert_string_equal(cfg.nodes[0].exe, "/opt/c/bin/node");
    assert_string_equal(cfg.nodes[0].workdir, "/srv/cave");
    assert_string_equal(cfg.nodes[0].config, "cave.json");
    assert_string_equal(cfg.nodes[0].display, ":1");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4], \"exe\": 1}"),
                 "nodes[0].exe");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4], \"display\": [0]}"),
                 "nodes[0].display");
}

/* Parses json (which must load) and returns its unknown-key lines joined by '|'. */
static const char *unknown_lines(const char *json)
{
    static char lines[4096];
    char err[512] = "";
    if (cluster_config_parse(json, strlen(json), "keys.json", &cfg, err, sizeof err) != 0)
        fail_msg("%s", err);
    lines[0] = '\0';
    for (int i = 0; i < cfg.unknown_key_count && i < CLUSTER_MAX_UNKNOWN_KEYS; i++) {
        assert_null(strchr(cfg.unknown_keys[i], '\n'));
        snprintf(lines + strlen(lines), sizeof lines - strlen(lines), "%s|", cfg.unknown_keys[i]);
    }
    return lines;
}

/* A key no section reads is kept as one line naming the file, the field and the nearest
 * valid key of that section; the config still loads (the program warns, or refuses with
 * --strict). Keys are matched per section: "resolution" is valid on a node, not on a
 * screen. */
static void test_unknown_keys(void **state)
{
    char buf[2048];
    const char *node = "{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4]";
    snprintf(buf, sizeof buf, "%s \"nodes\": [%s}]}", good_head, node);
    assert_string_equal(unknown_lines(buf), "");
    assert_int_equal(cfg.unknown_key_count, 0);

    snprintf(buf, sizeof buf, "%s \"nodes\": [%s, \"resolutoin\": [8,8]}]}", good_head, node);
    assert_string_equal(unknown_lines(buf), "cluster config keys.json: field nodes[0].resolutoin: unknown key "
                        "\"resolutoin\" (did you mean \"resolution\"?)|");
    assert_int_equal(cfg.nodes[0].screens[0].width, 4); /* nothing else changed */

    snprintf(buf, sizeof buf, "%s \"nodes\": [{\"name\": \"a\", \"scren\": 1, \"screens\": [\"s\"], "
             "\"resolution\": [4,4]}]}", good_head);
    assert_non_null(strstr(unknown_lines(buf), "field nodes[0].scren: unknown key \"scren\" (did you mean \"screens\"?)"));

    /* Nested sections, several at once, and a key with nothing near it. */
    snprintf(buf, sizeof buf, "{\"master\": {\"bind\": \"tcp://*:5570\", \"connect\": \"tcp://h:5570\", "
             "\"conect\": 1}, \"observer\": {\"tracker_to_cave\": {\"scael\": 2}}, \"screens\": "
             "[{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [0,1,0], "
             "\"resolution\": [4,4]}], \"zzzzzz\": 0, \"nodes\": [%s}]}", node);
    const char *l = unknown_lines(buf);
    assert_int_equal(cfg.unknown_key_count, 4);
    assert_non_null(strstr(l, "field master.conect: unknown key \"conect\" (did you mean \"connect\"?)"));
    assert_non_null(strstr(l, "field observer.tracker_to_cave.scael: unknown key \"scael\" (did you mean \"scale\"?)"));
    assert_non_null(strstr(l, "field screens[0].resolution: unknown key \"resolution\" (keys here: name, "));
    assert_non_null(strstr(l, "field zzzzzz: unknown key \"zzzzzz\" (keys here: name, scene, app, launch, scene_transform, master"));
}

/* The display keys: a node's window (monitor by index or name, placement, vsync, swap group)
 * and a screen's projector warp, whose file is found beside the config. */
static void test_display_keys(void **state)
{
    char buf[2048], err[512] = "";
#define NODE(x) (snprintf(buf, sizeof buf, "%s \"nodes\": [{\"name\": \"a\", \"screens\": [\"s\"], " \
                          "\"resolution\": [4,4]%s}]}", good_head, x), buf)
    const char *plain = NODE("");
    assert_int_equal(cluster_config_parse(plain, strlen(plain), "cfg/ok.json", &cfg, err, sizeof err), 0);
    const cluster_window *w = &cfg.nodes[0].window;
    assert_int_equal(w->monitor[0], 0);
    assert_int_equal(w->monitor[1], 1);
    assert_string_equal(w->monitor_name[0], "");
    assert_int_equal(w->swap_interval, 1); /* vsync on unless said otherwise */
    assert_int_equal(w->have_position, 0);
    assert_int_equal(w->swap_group, 0);
    assert_int_equal(cfg.nodes[0].screens[0].warp.kind, CLUSTER_WARP_NONE);
    const char *full = NODE(", \"monitor\": [\"DP-1\", 3], \"fullscreen\": true, \"position\": [1920, -10], "
                            "\"size\": [800, 600], \"vsync\": 2, \"swap_group\": 1, \"swap_barrier\": 1");
    assert_int_equal(cluster_config_parse(full, strlen(full), "cfg/ok.json", &cfg, err, sizeof err), 0);
    assert_string_equal(w->monitor_name[0], "DP-1");
    assert_int_equal(w->monitor[1], 3);
    assert_int_equal(w->fullscreen, 1);
    assert_int_equal(w->position[0], 1920);
    assert_int_equal(w->position[1], -10);
    assert_int_equal(w->have_position, 1);
    assert_int_equal(w->size[0], 800);
    assert_int_equal(w->swap_interval, 2);
    assert_int_equal(w->swap_group, 1);
    assert_int_equal(w->swap_barrier, 1);
    const char *off = NODE(", \"monitor\": 2, \"vsync\": false");
    assert_int_equal(cluster_config_parse(off, strlen(off), "ok.json", &cfg, err, sizeof err), 0);
    assert_int_equal(w->monitor[0], 2);
    assert_int_equal(w->monitor[1], 3); /* window-per-eye: the right eye on the next monitor */
    assert_int_equal(w->swap_interval, 0);
    expect_error(NODE(", \"monitor\": -1"), "nodes[0].monitor");
    expect_error(NODE(", \"monitor\": [0]"), "nodes[0].monitor");
    expect_error(NODE(", \"vsync\": \"yes\""), "nodes[0].vsync");
    expect_error(NODE(", \"position\": [1]"), "nodes[0].position");
    expect_error(NODE(", \"size\": [0, 10]"), "nodes[0].size");
    expect_error(NODE(", \"swap_barrier\": 1"), "nodes[0].swap_barrier"); /* a barrier binds a group */
#undef NODE
#define WARP(x) (snprintf(buf, sizeof buf, "%s \"nodes\": [{\"name\": \"a\", \"screens\": [{\"name\": \"s\", " \
                          "\"resolution\": [4,4], \"warp\": %s}]}]}", good_head, x), buf)
    const char *mpcdi = WARP("{\"mpcdi\": \"wall.mpcdi\", \"region\": \"p1\", "
                             "\"to_cave\": {\"translation\": [0, 0, -1.5]}}");
    assert_int_equal(cluster_config_parse(mpcdi, strlen(mpcdi), "cfg/ok.json", &cfg, err, sizeof err), 0);
    const cluster_warp *wp = &cfg.nodes[0].screens[0].warp;
    assert_int_equal(wp->kind, CLUSTER_WARP_MPCDI);
    assert_string_equal(wp->path, "cfg/wall.mpcdi"); /* beside the config */
    assert_string_equal(wp->region, "p1");
    assert_float_equal(wp->to_cave[14], -1.5f, 1e-6);
    const char *mesh = WARP("{\"mesh\": \"/etc/cave/left.warp\"}");
    assert_int_equal(cluster_config_parse(mesh, strlen(mesh), "cfg/ok.json", &cfg, err, sizeof err), 0);
    assert_int_equal(wp->kind, CLUSTER_WARP_MESH);
    assert_string_equal(wp->path, "/etc/cave/left.warp");
    assert_float_equal(wp->to_cave[0], 1.0f, 0);
    expect_error(WARP("\"wall.mpcdi\""), "nodes[0].screens[0].warp");
    expect_error(WARP("{\"mpcdi\": \"a\", \"mesh\": \"b\"}"), "nodes[0].screens[0].warp");
    expect_error(WARP("{\"mesh\": \"b\", \"region\": \"p1\"}"), "nodes[0].screens[0].warp");
    expect_error(WARP("{\"mpcdi\": \"a\", \"region\": 3}"), "nodes[0].screens[0].warp.region");
    expect_error(WARP("{\"mpcdi\": \"a\", \"to_cave\": {\"scale\": 0}}"), "nodes[0].screens[0].warp.to_cave.scale");
#undef WARP
}

/* A required key that is missing beside a member that looks like it: both named. */
static void expect_misspelt(const char *json, const char *line)
{
    char err[512] = "";
    assert_int_equal(cluster_config_parse(json, strlen(json), "bad.json", &cfg, err, sizeof err), -1);
    if (!strstr(err, line))
        fail_msg("error '%s' is not '%s'", err, line);
}

static void test_misspelt_required_keys(void **state)
{
    (void)state;
    char buf[2048];
    expect_misspelt(NODES("{\"nmae\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4]}"),
                    "field nodes[0].name: missing (a string is required; \"nmae\" here is \"name\" misspelt?)");
    expect_misspelt(NODES("{\"name\": \"a\", \"scren\": [\"s\"], \"resolution\": [4,4]}"),
                    "field nodes[0].screens: missing (an array of screen names is required; \"scren\" here is "
                    "\"screens\" misspelt?)");
    expect_misspelt("{\"mastr\": {}, \"screens\": []}", "field master: missing (an object is required: "
                    "{\"bind\": ..., \"connect\": ...}; \"mastr\" here is \"master\" misspelt?)");
    snprintf(buf, sizeof buf, "%s \"nodez\": []}", good_head);
    expect_misspelt(buf, "field nodes: missing (an array of nodes is required; \"nodez\" here is \"nodes\" misspelt?)");
    /* Nothing close: only what is missing. */
    expect_misspelt(NODES("{\"host\": \"h\", \"screens\": [\"s\"], \"resolution\": [4,4]}"),
                    "field nodes[0].name: missing (a string is required)");
}

static void test_missing_file(void **state)
{
    char err[512] = "";
    assert_int_equal(cluster_config_load("/nonexistent/x.json", &cfg, err, sizeof err), -1);
    assert_non_null(strstr(err, "/nonexistent/x.json"));
}

static void test_tracker_transform(void **state)
{
    char buf[2048], err[512] = "";
    snprintf(buf, sizeof buf, "%s \"observer\": {\"tracker_to_cave\": {\"translation\": [1,2,3],"
             " \"rotation_deg\": [0, 90, 0], \"scale\": 0.001}}, \"nodes\": [{\"name\": \"a\","
             " \"screens\": [\"s\"], \"resolution\": [4,4]}]}", good_head);
    assert_int_equal(cluster_config_parse(buf, strlen(buf), "t.json", &cfg, err, sizeof err), 0);
    const float *m = cfg.observer.tracker_to_cave;
    /* x axis of the tracker (1000 mm) maps to -z in the CAVE after a 90 degree yaw. */
    float x = m[0] * 1000 + m[12], z = m[2] * 1000 + m[14];
    assert_float_equal(x, 1.0f, 1e-5);
    assert_float_equal(z, 2.0f, 1e-5);
    assert_float_equal(m[13], 2.0f, 0);
}

/* A one-screen config with the given corner fields and top-level extras. */
static int parse_screen(const char *corners, const char *extra, char *err, size_t errlen)
{
    static char buf[2048];
    snprintf(buf, sizeof buf, "{\"master\": {\"bind\": \"tcp://*:1\", \"connect\": \"tcp://h:1\"}, %s"
             "\"screens\": [{\"name\": \"s\", %s}], \"nodes\": [{\"name\": \"a\", \"screens\": [\"s\"],"
             " \"resolution\": [4,4]}]}", extra, corners);
    return cluster_config_parse(buf, strlen(buf), "m.json", &cfg, err, errlen);
}

/* Sum of squared distances between given corners (3 or 4) and a rectangle's. */
static double fit_error(const float g[4][3], int n, const float bl[3], const float br[3], const float tl[3])
{
    double e = 0;
    for (int i = 0; i < 3; i++) {
        double q[4] = {bl[i], br[i], tl[i], br[i] + tl[i] - bl[i]};
        for (int k = 0; k < n; k++)
            e += (q[k] - g[k][i]) * (q[k] - g[k][i]);
    }
    return e;
}

/* Rodrigues: v rotated by angle about the unit axis k. */
static void rotate(const double k[3], double angle, const double v[3], double out[3])
{
    double c = cos(angle), s = sin(angle), kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    double x[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int i = 0; i < 3; i++)
        out[i] = v[i] * c + x[i] * s + k[i] * kv * (1 - c);
}

/* Measured corners: a 5 mm error is fitted (today's |cos| < 1e-3 check refused it), the
 * fit is a rectangle, least squares (no nearby rectangle does better), and a corner beyond
 * the tolerance is refused in millimetres. */
static void test_measured_corners(void **state)
{
    char err[512] = "";
    /* cave5's front-l half wall, top-left corner 5 mm off to the right and 1 mm off the wall. */
    const float given[4][3] = {{-1.5f, 0, -1.5f}, {0, 0, -1.5f}, {-1.495f, 3, -1.499f}};
    assert_int_equal(parse_screen("\"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [0,0,-1.5],"
                                  " \"top_left\": [-1.495,3,-1.499]", "", err, sizeof err), 0);
    const cluster_screen *sc = &cfg.screens[0];
    assert_true(sc->fit_mm > 1.0f && sc->fit_mm < 5.1f);
    float u[3], w[3], uw = 0;
    for (int i = 0; i < 3; i++) {
        u[i] = sc->bottom_right[i] - sc->bottom_left[i];
        w[i] = sc->top_left[i] - sc->bottom_left[i];
        uw += u[i] * w[i];
    }
    assert_true(fabsf(uw) < 1e-6f * 1.5f * 3.0f);
    assert_true(dist(sc->top_left, given[2]) <= sc->fit_mm / 1000 + 1e-6f);
    /* Least squares: 400 nearby rectangles (turned, moved, resized) all fit worse. */
    double best = fit_error(given, 3, sc->bottom_left, sc->bottom_right, sc->top_left);
    double c[3], e1[3], e2[3], a = dist(sc->bottom_right, sc->bottom_left) / 2,
           b = dist(sc->top_left, sc->bottom_left) / 2;
    for (int i = 0; i < 3; i++) {
        c[i] = sc->bottom_left[i] + 0.5 * (u[i] + w[i]);
        e1[i] = u[i] / (2 * a);
        e2[i] = w[i] / (2 * b);
    }
    unsigned seed = 12345;
    for (int t = 0; t < 400; t++) {
        double r[8];
        for (int k = 0; k < 8; k++) {
            seed = seed * 1103515245u + 12345u;
            r[k] = ((seed >> 8) / (double)(1u << 24) - 0.5) * 2e-3;
        }
        double axis[3] = {r[0], r[1], r[2]}, len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        for (int i = 0; i < 3; i++)
            axis[i] /= len;
        double f1[3], f2[3];
        rotate(axis, len, e1, f1);
        rotate(axis, len, e2, f2);
        float bl[3], br[3], tl[3];
        for (int i = 0; i < 3; i++) {
            double cc = c[i] + r[3 + i % 3] * (i == 0 ? 1 : i == 1 ? 0.7 : 0.4);
            double aa = a + r[6], bb = b + r[7];
            bl[i] = (float)(cc - aa * f1[i] - bb * f2[i]);
            br[i] = (float)(cc + aa * f1[i] - bb * f2[i]);
            tl[i] = (float)(cc - aa * f1[i] + bb * f2[i]);
        }
        assert_true(fit_error(given, 3, bl, br, tl) >= best * (1 - 1e-4));
    }
    /* Four corners of a keystoned screen (top 2 cm narrower): by symmetry the nearest
     * rectangle is 1.99 m x 1 m, each corner 5 mm in or out. */
    assert_int_equal(parse_screen("\"bottom_left\": [0,0,0], \"bottom_right\": [2,0,0], \"top_left\": [0.01,1,0],"
                                  " \"top_right\": [1.99,1,0]", "", err, sizeof err), 0);
    assert_float_equal(cfg.screens[0].fit_mm, 5.0f, 1e-3);
    assert_float_equal(cfg.screens[0].bottom_left[0], 0.005f, 1e-6);
    assert_float_equal(cfg.screens[0].bottom_right[0], 1.995f, 1e-6);
    assert_float_equal(cfg.screens[0].top_left[1], 1.0f, 1e-6);
    /* 30 mm of shear: refused, in millimetres; a larger tolerance takes it. */
    const char *sheared = "\"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [0.06,1,0]";
    assert_int_equal(parse_screen(sheared, "", err, sizeof err), -1);
    assert_non_null(strstr(err, "screens[0]: 's' corners are "));
    assert_non_null(strstr(err, " mm from the nearest rectangle, more than corner_tolerance_mm 20"));
    assert_int_equal(parse_screen(sheared, "\"corner_tolerance_mm\": 50,", err, sizeof err), 0);
    /* An exact rectangle stays exactly as written. */
    assert_int_equal(parse_screen("\"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [0,0,-1.5],"
                                  " \"top_left\": [-1.5,3,-1.5]", "", err, sizeof err), 0);
    assert_true(cfg.screens[0].fit_mm < 1e-3f);
    assert_true(cfg.screens[0].top_left[0] == -1.5f && cfg.screens[0].top_left[1] == 3.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_measured_corners),
        cmocka_unit_test(test_shipped_configs),
        cmocka_unit_test(test_bad_configs),
        cmocka_unit_test(test_unknown_keys),
        cmocka_unit_test(test_display_keys),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_misspelt_required_keys),
        cmocka_unit_test(test_tracker_transform),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
