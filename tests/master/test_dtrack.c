/* DTrack2 ASCII parser and UDP source: recorded-style and synthetic datagrams, including
 * truncated, oversized, non-numeric and NaN input; real UDP sockets for the source: the
 * port is not shared, only the configured sender counts, silence and resumption are said
 * once each and rate-limited; a scaled tracker transform keeps orientations orthonormal. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <arpa/inet.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "base/ratelog.h"
#include "cluster/cluster_config.h"
#include "input/input.h"
#include "input/input_config.h"
#include "input/input_dtrack.h"

static char *load(const char *name, size_t *len)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/tests/fuzz/dtrack/%s", CAVELIGHT_SOURCE_DIR, name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char buf[8192];
    *len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    return buf;
}

static void test_full_frame(void **state)
{
    size_t len;
    const char *d = load("frame_full.txt", &len);
    static input_dtrack_frame f;
    assert_int_equal(input_dtrack_parse(d, len, &f), 0);
    assert_int_equal(f.lines_parsed, 6);
    assert_true(f.has_frame);
    assert_int_equal(f.frame, 21753);
    assert_true(f.has_timestamp);
    assert_float_equal(f.timestamp, 39596.024831, 1e-9);
    assert_int_equal(f.calibrated_bodies, 2);
    assert_int_equal(f.body_count, 2);
    /* millimetres to metres */
    assert_float_equal(f.bodies[0].position[0], 0.326848f, 1e-6);
    assert_float_equal(f.bodies[0].position[1], -0.187216f, 1e-6);
    assert_float_equal(f.bodies[0].position[2], 1.709503f, 1e-6);
    /* b0..b8 kept in order: column-wise */
    assert_float_equal(f.bodies[0].rotation[0], -0.940508f, 1e-7);
    assert_float_equal(f.bodies[0].rotation[3], 0.328234f, 1e-7);
    assert_float_equal(f.bodies[0].rotation[8], 0.976081f, 1e-7);
    assert_int_equal(f.bodies[1].id, 1);
    assert_float_equal(f.bodies[1].rotation[5], -1.0f, 0);
    assert_int_equal(f.flystick_count, 1);
    const input_dtrack_flystick *s = &f.flysticks[0];
    assert_int_equal(s->id, 0);
    assert_int_equal(s->button_count, 6);
    assert_int_equal(s->buttons, 5);
    assert_int_equal(s->controller_count, 2);
    assert_float_equal(s->controllers[0], -0.5f, 0);
    assert_float_equal(s->controllers[1], 0.75f, 0);
    assert_float_equal(s->position[1], 1.2005f, 1e-6);
    assert_float_equal(s->rotation[2], -1.0f, 0);
    assert_int_equal(f.marker_count, 2);
    assert_int_equal(f.markers[0].id, 24);
    assert_float_equal(f.markers[0].position[2], 0.2309f, 1e-6);
}

static void test_unknown_and_extra_ignored(void **state)
{
    size_t len;
    const char *d = load("unknown_and_extra.txt", &len);
    static input_dtrack_frame f;
    assert_int_equal(input_dtrack_parse(d, len, &f), 0);
    assert_int_equal(f.lines_parsed, 2);   /* fr, 6d */
    assert_int_equal(f.lines_ignored, 3);  /* 6dmt, gl, xyz */
    assert_int_equal(f.body_count, 1);
    /* DTrack1-style 6 values (with angles): the first three are the position */
    assert_float_equal(f.bodies[0].position[0], 0.001f, 1e-9);
    assert_float_equal(f.bodies[0].position[2], 0.003f, 1e-9);
    assert_float_equal(f.bodies[0].rotation[8], 1.0f, 0);
}

static void test_bad_values_dropped(void **state)
{
    size_t len;
    const char *d = load("bad_values.txt", &len);
    static input_dtrack_frame f;
    assert_int_equal(input_dtrack_parse(d, len, &f), 3);
    assert_int_equal(f.lines_parsed, 1);
    assert_int_equal(f.body_count, 0);
    assert_int_equal(f.marker_count, 0);

    const char *cases[] = {
        "6d 1 [0 1.0][1 2 3][1 0 0 0 1 0 0 0 inf]",
        "6d 1 [0 1.0][1 2 3][1 0 0 0 1 0 0 0 NaN]",
        "6d 1 [zero 1.0][1 2 3][1 0 0 0 1 0 0 0 1]",
        "6d 1 [0 1.0][1 2 3x][1 0 0 0 1 0 0 0 1]",
        "6d 1 [0 1.0][1 2][1 0 0 0 1 0 0 0 1]",           /* too few values */
        "6d 2 [0 1.0][1 2 3][1 0 0 0 1 0 0 0 1]",         /* count says 2 */
        "6d 1.5 [0 1.0][1 2 3][1 0 0 0 1 0 0 0 1]",
        "6d -1",
        "6d 33",                                          /* over the body limit */
        "6d 1 [-3 1.0][1 2 3][1 0 0 0 1 0 0 0 1]",        /* negative id */
        "6df2 1 1 [0 1.0 2000 0][1 2 3][1 0 0 0 1 0 0 0 1][0]", /* absurd button count */
        "6df2 1 1 [0 1.0 6 2][1 2 3][1 0 0 0 1 0 0 0 1][5 0.5]", /* missing controller */
        "6df2 1 1 [0 1.0 6 2][1 2 3][1 0 0 0 1 0 0 0 1][-5 0.5 0.5]",
        "fr abc",
        "fr 99999999999",
        "ts -1",
        "3d 1 [0 1][0 0 0",
        "6d 1 [0 1.0][1e39 0 0][1 0 0 0 1 0 0 0 1]",       /* beyond float (found by fuzzing) */
        "6d 1 [0 1.0][1 2 3][1 0 0 0 1 0 0 0 1000000000000000000000000000000000000000000000000000000000000001]",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int bad = input_dtrack_parse(cases[i], strlen(cases[i]), &f);
        if (bad != 1)
            fail_msg("case %zu accepted: %s", i, cases[i]);
        assert_int_equal(f.body_count + f.flystick_count + f.marker_count, 0);
        assert_false(f.has_frame || f.has_timestamp);
    }
}

/* Every prefix of a valid datagram parses without reading past it, and a line is either
 * accepted whole or dropped: the body count never includes a half-parsed body. */
static void test_truncated_prefixes(void **state)
{
    size_t len;
    const char *d = load("frame_full.txt", &len);
    static input_dtrack_frame f, full;
    input_dtrack_parse(d, len, &full);
    for (size_t n = 0; n <= len; n++) {
        char *copy = malloc(n ? n : 1); /* exact size: ASan/valgrind catch overreads */
        memcpy(copy, d, n);
        input_dtrack_parse(copy, n, &f);
        free(copy);
        assert_true(f.body_count == 0 || f.body_count == 2);
        assert_true(f.flystick_count == 0 || f.flystick_count == 1);
        assert_true(f.marker_count == 0 || f.marker_count == 2);
        if (f.body_count == 2)
            assert_memory_equal(f.bodies, full.bodies, 2 * sizeof f.bodies[0]);
        assert_true(f.lines_bad <= 1);
    }
}

static void test_oversized(void **state)
{
    /* 200 KiB of body lines: the limit keeps 32 bodies, the rest of the lines drop. */
    const char *line = "6d 1 [0 1.0][1 2 3][1 0 0 0 1 0 0 0 1]\n";
    size_t ll = strlen(line), n = 200 * 1024 / ll;
    char *big = malloc(n * ll);
    for (size_t i = 0; i < n; i++)
        memcpy(big + i * ll, line, ll);
    static input_dtrack_frame f;
    int bad = input_dtrack_parse(big, n * ll, &f);
    assert_int_equal(f.body_count, INPUT_DTRACK_MAX_BODIES);
    assert_int_equal(bad, (int)n - INPUT_DTRACK_MAX_BODIES);
    /* One endless block and one endless token: rejected, not stored. */
    memset(big, '1', n * ll);
    memcpy(big, "6d 1 [", 6);
    assert_int_equal(input_dtrack_parse(big, n * ll, &f), 1);
    for (size_t i = 6; i < n * ll; i += 2)
        big[i] = ' ';
    assert_int_equal(input_dtrack_parse(big, n * ll, &f), 1);
    assert_int_equal(f.body_count, 0);
    free(big);
    /* NUL bytes and binary junk are just bad or unknown lines. */
    const char junk[] = "fr 1\n\0\0\xff\xfe 6d\n6d 1 [0 1\0][1 2 3][1 0 0 0 1 0 0 0 1]\nts 5.5";
    input_dtrack_parse(junk, sizeof junk - 1, &f);
    assert_true(f.has_frame);
    assert_true(f.has_timestamp);
    assert_int_equal(f.body_count, 0);
}

static void test_apply_mapping(void **state)
{
    size_t len;
    const char *d = load("flystick_untracked.txt", &len);
    static input_dtrack_frame f;
    assert_int_equal(input_dtrack_parse(d, len, &f), 0);
    assert_int_equal(f.flystick_count, 2);
    assert_int_equal(f.flysticks[0].buttons, 129);
    assert_int_equal(f.flysticks[1].buttons, 15);

    /* raw 0 -> C (trigger), raw 7 -> R; untracked flystick: buttons yes, pose no */
    input_dtrack_desc desc = {.head_id = 0, .wand_id = 0};
    desc.buttons.set = 1;
    memset(desc.buttons.to, -1, sizeof desc.buttons.to);
    desc.buttons.to[0] = INPUT_BUTTON_C;
    desc.buttons.to[7] = INPUT_BUTTON_R;
    input_source_state st = {0};
    input_dtrack_apply(&desc, &f, &st, 1.0);
    assert_false(st.head.valid);
    assert_false(st.wand.valid);
    assert_int_equal(st.buttons, (1u << INPUT_BUTTON_C) | (1u << INPUT_BUTTON_R));
    assert_int_equal(st.pressed, st.buttons);
    assert_float_equal(st.axes[INPUT_AXIS_Y], -1.0f, 0);

    /* flystick 1 is tracked: identity map keeps its 4 buttons, pose in metres */
    input_dtrack_desc d1 = {.head_id = 5, .wand_id = 1};
    input_source_state s1 = {0};
    input_dtrack_apply(&d1, &f, &s1, 2.0);
    assert_true(s1.wand.valid);
    assert_float_equal(s1.wand.position[2], 0.3f, 1e-6);
    assert_int_equal(s1.buttons, 15);
    assert_float_equal(s1.wand.time, 2.0, 0);

    /* a wand given as a 6d body */
    const char *b = "6d 2 [0 1][0 1700 0][1 0 0 0 1 0 0 0 1] [3 1][100 1000 -200][1 0 0 0 1 0 0 0 1]";
    input_dtrack_parse(b, strlen(b), &f);
    input_dtrack_desc d2 = {.head_id = 0, .wand_id = 3, .wand_kind = INPUT_DTRACK_WAND_BODY};
    input_source_state s2 = {0};
    input_dtrack_apply(&d2, &f, &s2, 3.0);
    assert_true(s2.head.valid && s2.wand.valid);
    assert_float_equal(s2.head.position[1], 1.7f, 1e-6);
    assert_float_equal(s2.wand.position[0], 0.1f, 1e-6);
    assert_int_equal(s2.buttons, 0);
}

/* One datagram to 127.0.0.1:port from the loopback address `from` (NULL: the default). */
static void send_from(const char *from, int port, const char *msg)
{
    int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (from) {
        struct sockaddr_in b = {.sin_family = AF_INET};
        inet_pton(AF_INET, from, &b.sin_addr);
        assert_int_equal(bind(fd, (struct sockaddr *)&b, sizeof b), 0);
    }
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port)};
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    assert_int_equal(sendto(fd, msg, strlen(msg), 0, (struct sockaddr *)&a, sizeof a),
                     (ssize_t)strlen(msg));
    close(fd);
}

static void send_to(int port, const char *msg) { send_from(NULL, port, msg); }

static void sleep_s(double s)
{
    nanosleep(&(struct timespec){(time_t)s, (long)((s - (time_t)s) * 1e9)}, NULL);
}

/* Real UDP: datagrams in, merged state out, with the tracker-to-CAVE transform applied
 * (here a translation by (0, 0, -1.5) and a 90 degree turn about Y). */
static void test_udp_source(void **state)
{
    char err[256];
    input_desc desc = {0};
    float m[16] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, -1.5f, 1};
    memcpy(desc.tracker_to_cave, m, sizeof m);
    input *in = input_create(&desc, err, sizeof err);
    assert_non_null(in);
    /* silence_s: a loaded machine must not see an outage between two polls here */
    input_dtrack_desc dd = {.name = "art", .port = 0, .head_id = 0, .wand_id = 0, .silence_s = 3600};
    input_source *src = input_dtrack_open(&dd, err, sizeof err);
    assert_non_null(src);
    int port = input_dtrack_port(src);
    assert_true(port > 0);
    assert_int_equal(input_add_source(in, src, err, sizeof err), 0);

    input_state s;
    assert_int_equal(input_poll(in, &s, err, sizeof err), 0);
    assert_false(s.head.valid);

    send_to(port, "fr 1\n6d 1 [0 1.0][1000 1700 0][1 0 0 0 1 0 0 0 1]\n"
                  "6df2 1 1 [0 1.0 4 2][0 1000 -500][1 0 0 0 1 0 0 0 1][4 0.25 -0.5]\n");
    send_to(port, "fr 2\n6df2 1 1 [0 1.0 4 2][0 1000 -500][1 0 0 0 1 0 0 0 1][0 0.25 -0.5]\n");
    nanosleep(&(struct timespec){0, 20000000}, NULL);
    assert_int_equal(input_poll(in, &s, err, sizeof err), 1); /* the first datagrams, announced */
    char want[64];
    snprintf(want, sizeof want, "input art: DTrack datagrams on UDP port %d", port);
    assert_string_equal(err, want);
    assert_true(s.head.valid && s.wand.valid);
    /* x=1 maps to -z, then shifted by -1.5 */
    assert_float_equal(s.head.position[0], 0.0f, 1e-6);
    assert_float_equal(s.head.position[1], 1.7f, 1e-6);
    assert_float_equal(s.head.position[2], -2.5f, 1e-6);
    assert_float_equal(s.head.rotation[2], -1.0f, 1e-6); /* column 0 = image of x */
    assert_float_equal(s.wand.position[0], -0.5f, 1e-6);
    /* button 2 (R) pressed and released within one poll: the press is kept */
    assert_int_equal(s.buttons, 0);
    assert_int_equal(s.pressed, 1u << INPUT_BUTTON_R);
    assert_float_equal(s.axes[INPUT_AXIS_X], 0.25f, 0);
    assert_float_equal(s.axes[INPUT_AXIS_Y], -0.5f, 0);
    assert_int_equal(input_poll(in, &s, err, sizeof err), 0);
    assert_int_equal(s.pressed, 0);
    input_close(in);
}

/* The port is this source's alone: a second socket cannot bind it, even with
 * SO_REUSEADDR (how a local user once read the head stream); and a port someone else
 * holds is refused in one line. */
static void test_port_not_shared(void **state)
{
    char err[512];
    input_source *src = input_dtrack_open(&(input_dtrack_desc){.name = "art", .port = 0}, err, sizeof err);
    assert_non_null(src);
    int port = input_dtrack_port(src);
    int thief = socket(AF_INET, SOCK_DGRAM, 0), one = 1;
    setsockopt(thief, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port)};
    assert_int_not_equal(bind(thief, (struct sockaddr *)&a, sizeof a), 0);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    assert_int_not_equal(bind(thief, (struct sockaddr *)&a, sizeof a), 0);
    close(thief);
    src->close(src);

    /* the other way round: someone holds the port first */
    thief = socket(AF_INET, SOCK_DGRAM, 0);
    setsockopt(thief, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    a.sin_port = 0;
    assert_int_equal(bind(thief, (struct sockaddr *)&a, sizeof a), 0);
    socklen_t alen = sizeof a;
    getsockname(thief, (struct sockaddr *)&a, &alen);
    port = ntohs(a.sin_port);
    err[0] = '\0';
    assert_null(input_dtrack_open(&(input_dtrack_desc){.name = "art", .port = port}, err, sizeof err));
    if (!strstr(err, "input art: cannot listen for DTrack on UDP 0.0.0.0:") || !strstr(err, "in use"))
        fail_msg("unclear refusal: %s", err);
    close(thief);
}

/* bind and sender: only the configured host moves the head; the others are dropped,
 * counted and logged at most once per poll. Bad addresses are refused in one line. */
static void test_bind_and_sender(void **state)
{
    char err[512];
    input *in = input_create(&(input_desc){0}, err, sizeof err);
    input_source *src = input_dtrack_open(&(input_dtrack_desc){.name = "art", .bind = "127.0.0.1",
                                                               .sender = "127.0.0.1", .silence_s = 3600},
                                          err, sizeof err);
    assert_non_null(src);
    int port = input_dtrack_port(src);
    input_add_source(in, src, err, sizeof err);
    for (int i = 0; i < 3; i++)
        send_from("127.0.0.2", port, "6d 1 [0 1.0][9000 9000 9000][1 0 0 0 1 0 0 0 1]\n");
    send_from("127.0.0.1", port, "6d 1 [0 1.0][0 1700 0][1 0 0 0 1 0 0 0 1]\n");
    sleep_s(0.02);
    input_state s;
    assert_int_equal(input_poll(in, &s, err, sizeof err), -1);
    char want[160];
    snprintf(want, sizeof want, "input art: datagrams from 127.0.0.2 on UDP 127.0.0.1:%d dropped: only "
             "127.0.0.1 may send (\"sender\" in the input config; 3 dropped so far)", port);
    assert_string_equal(err, want);
    assert_true(s.head.valid);
    assert_float_equal(s.head.position[0], 0.0f, 0);
    assert_float_equal(s.head.position[1], 1.7f, 1e-6);
    assert_int_equal(input_dtrack_refused(src), 3);
    assert_int_equal(input_dtrack_datagrams(src), 1);
    input_close(in);

    err[0] = '\0';
    assert_null(input_dtrack_open(&(input_dtrack_desc){.name = "art", .port = 0, .bind = "no-such-if0"},
                                  err, sizeof err));
    assert_non_null(strstr(err, "input art: \"bind\" no-such-if0 is neither an IPv4 address nor an interface"));
    err[0] = '\0';
    assert_null(input_dtrack_open(&(input_dtrack_desc){.name = "art", .port = 0, .sender = "no-such-host.invalid"},
                                  err, sizeof err));
    assert_non_null(strstr(err, "input art: \"sender\" no-such-host.invalid"));
    /* an interface name binds its address */
    input_source *lo = input_dtrack_open(&(input_dtrack_desc){.name = "art", .port = 0, .bind = "lo"},
                                         err, sizeof err);
    if (!lo)
        fail_msg("%s", err);
    lo->close(lo);
}

/* No datagram for silence_s: said once, buttons released, the pose kept; data again:
 * said once with the outage's length. A tracker that comes and goes is rate-limited. */
static void test_silence_and_resumption(void **state)
{
    char err[512];
    input *in = input_create(&(input_desc){0}, err, sizeof err);
    input_source *src = input_dtrack_open(&(input_dtrack_desc){.name = "art", .port = 0, .silence_s = 0.05},
                                          err, sizeof err);
    assert_non_null(src);
    int port = input_dtrack_port(src);
    input_add_source(in, src, err, sizeof err);
    const char *held = "6d 1 [0 1.0][0 1700 0][1 0 0 0 1 0 0 0 1]\n"
                       "6df2 1 1 [0 1.0 4 0][0 1000 -500][1 0 0 0 1 0 0 0 1][8]\n";
    send_to(port, held);
    sleep_s(0.01);
    input_state s;
    int lines = 0, rc = input_poll(in, &s, err, sizeof err);
    assert_int_equal(rc, 1);
    lines++;
    assert_int_equal(s.buttons, 1u << INPUT_BUTTON_C);
    sleep_s(0.1);
    assert_int_equal(input_poll(in, &s, err, sizeof err), -1);
    lines++;
    char want[96];
    snprintf(want, sizeof want, "input art: no DTrack datagram on UDP port %d for ", port);
    if (!strstr(err, want) || !strstr(err, "tracking stands still, buttons released, the session goes on"))
        fail_msg("silence line: %s", err);
    assert_int_equal(s.buttons, 0);       /* C (fly) does not stay held */
    assert_true(s.head.valid);            /* the last pose stays */
    assert_float_equal(s.head.position[1], 1.7f, 1e-6);
    assert_int_equal(input_poll(in, &s, err, sizeof err), 0); /* said once */
    send_to(port, held);
    sleep_s(0.01);
    assert_int_equal(input_poll(in, &s, err, sizeof err), 1);
    lines++;
    snprintf(want, sizeof want, "input art: DTrack datagrams on UDP port %d again after ", port);
    if (!strstr(err, want))
        fail_msg("resumption line: %s", err);
    /* Coming and going 20 times more: the source's lines stop at the ratelog burst. */
    for (int i = 0; i < 20; i++) {
        sleep_s(0.06);
        lines += input_poll(in, &s, err, sizeof err) != 0;
        send_to(port, held);
        sleep_s(0.005);
        lines += input_poll(in, &s, err, sizeof err) != 0;
    }
    assert_true(lines >= RATELOG_BURST && lines <= RATELOG_BURST + 1); /* +1: a run over 10 s */
    input_close(in);
}

/* tracker_to_cave with a scale (units) moves and scales positions, and turns orientations
 * without scaling them: the rotation stays orthonormal and equals the unscaled one's. */
static void test_scaled_transform_keeps_rotation(void **state)
{
    const char *fmt = "{\"master\": {\"bind\": \"tcp://127.0.0.1:1\", \"connect\": \"tcp://127.0.0.1:1\"},"
                      " \"security\": {\"mode\": \"insecure\"},"
                      " \"observer\": {\"tracker_to_cave\": {\"translation\": [0.1, -0.2, 1.5],"
                      " \"rotation_deg\": [30, -45, 60], \"scale\": %s}},"
                      " \"screens\": [{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0],"
                      " \"top_left\": [0,1,0]}], \"nodes\": [{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4, 4]}]}";
    static cluster_config scaled, unit;
    char text[1024], err[512];
    snprintf(text, sizeof text, fmt, "0.001");
    if (cluster_config_parse(text, strlen(text), "scaled.json", &scaled, err, sizeof err) != 0)
        fail_msg("%s", err);
    snprintf(text, sizeof text, fmt, "1");
    if (cluster_config_parse(text, strlen(text), "unit.json", &unit, err, sizeof err) != 0)
        fail_msg("%s", err);
    /* a head turned 90 degrees about y, 1000 units from the tracker's origin */
    input_pose head = {.valid = 1, .position = {1000, 1700, -300}, .rotation = {0, 0, -1, 0, 1, 0, 1, 0, 0}};
    input_pose a = head, b = head;
    input_pose_transform(&a, scaled.observer.tracker_to_cave);
    input_pose_transform(&b, unit.observer.tracker_to_cave);
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) {
            float dot = 0.0f;
            for (int r = 0; r < 3; r++)
                dot += a.rotation[i * 3 + r] * a.rotation[k * 3 + r];
            assert_float_equal(dot, i == k ? 1.0f : 0.0f, 1e-5);
        }
    for (int i = 0; i < 9; i++)
        assert_float_equal(a.rotation[i], b.rotation[i], 1e-6);
    const float *t = unit.observer.tracker_to_cave;
    for (int r = 0; r < 3; r++) /* position: R (s p) + t */
        assert_float_equal(a.position[r], b.position[r] * 0.001f + t[12 + r] * (1 - 0.001f), 1e-4);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_config_errors(void **state)
{
    char path[1024], err[512];
    snprintf(path, sizeof path, "%s/test_dtrack_config.json", CAVELIGHT_BINARY_DIR);
    input_desc desc = {.path = path};
    const char *bad[][2] = {
        {"{\"sources\": []}", "non-empty"},
        {"{\"sources\": [{\"type\": \"teleport\"}]}", "unknown type \"teleport\""},
        {"{\"sources\": [{\"name\": \"art\"}]}", "no \"type\""},
        {"{\"sources\": [{\"type\": \"dtrack\", \"port\": 0, \"buttons\": [\"Q\"]}]}", "\"Q\""},
        {"{\"sources\": [{\"type\": \"dtrack\", \"port\": 0, \"wand_kind\": \"glove\"}]}", "glove"},
        {"not json", "not a JSON object"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_file(path, bad[i][0]);
        err[0] = '\0';
        assert_null(input_open(&desc, err, sizeof err));
        if (!strstr(err, bad[i][1]) || !strstr(err, path))
            fail_msg("case %zu: message \"%s\" lacks \"%s\" or the path", i, err, bad[i][1]);
    }
    write_file(path, "{\"sources\": [{\"type\": \"dtrack\", \"name\": \"art\", \"port\": 0, "
                     "\"head\": 2, \"wand\": 1, \"buttons\": [\"C\", \"R\", null, \"L\"], "
                     "\"axes\": [\"X\", \"Y\"]}]}");
    input *in = input_open(&desc, err, sizeof err);
    if (!in)
        fail_msg("%s", err);
    input_close(in);
    remove(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_full_frame),
        cmocka_unit_test(test_unknown_and_extra_ignored),
        cmocka_unit_test(test_bad_values_dropped),
        cmocka_unit_test(test_truncated_prefixes),
        cmocka_unit_test(test_oversized),
        cmocka_unit_test(test_apply_mapping),
        cmocka_unit_test(test_udp_source),
        cmocka_unit_test(test_port_not_shared),
        cmocka_unit_test(test_bind_and_sender),
        cmocka_unit_test(test_silence_and_resumption),
        cmocka_unit_test(test_scaled_transform_keeps_rotation),
        cmocka_unit_test(test_config_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
