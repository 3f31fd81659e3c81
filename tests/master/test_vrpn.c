/* VRPN client: synthetic streams (descriptions, tracker, buttons, analogs, truncated,
 * oversized, NaN and non-integer input) and a real TCP server process (tests/vrpn) that
 * is killed and restarted to check reconnection. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "input/input.h"
#include "input/input_config.h"
#include "input/input_vrpn.h"

static void be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24); p[1] = (uint8_t)(v >> 16); p[2] = (uint8_t)(v >> 8); p[3] = (uint8_t)v;
}

static void bef64(uint8_t *p, double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    be32(p, (uint32_t)(u >> 32));
    be32(p + 4, (uint32_t)u);
}

typedef struct stream {
    uint8_t b[8192];
    size_t n;
} stream;

static void add(stream *s, int32_t sender, int32_t type, const uint8_t *body, size_t len)
{
    size_t k = input_vrpn_frame(s->b + s->n, sizeof s->b - s->n, sender, type, body, len);
    assert_true(k >= 24 + len && k % 8 == 0);
    s->n += k;
}

static void add_name(stream *s, int32_t id, int32_t kind, const char *name)
{
    uint8_t b[80];
    be32(b, (uint32_t)strlen(name) + 1);
    memcpy(b + 4, name, strlen(name) + 1);
    add(s, id, kind, b, 4 + strlen(name) + 1);
}

static void add_pos_quat(stream *s, int sensor, const double v[7])
{
    uint8_t b[64] = {0};
    be32(b, (uint32_t)sensor);
    for (int i = 0; i < 7; i++)
        bef64(b + 8 + 8 * i, v[i]);
    add(s, 11, 40, b, sizeof b);
}

static void add_analog(stream *s, double n, double a, double b2)
{
    uint8_t b[24];
    bef64(b, n);
    bef64(b + 8, a);
    bef64(b + 16, b2);
    add(s, 12, 43, b, sizeof b);
}

static void preamble(stream *s)
{
    add_name(s, 11, INPUT_VRPN_SENDER_DESCRIPTION, "Tracker0");
    add_name(s, 12, INPUT_VRPN_SENDER_DESCRIPTION, "Wand0");
    add_name(s, 40, INPUT_VRPN_TYPE_DESCRIPTION, "vrpn_Tracker Pos_Quat");
    add_name(s, 41, INPUT_VRPN_TYPE_DESCRIPTION, "vrpn_Button Change");
    add_name(s, 42, INPUT_VRPN_TYPE_DESCRIPTION, "vrpn_Button States");
    add_name(s, 43, INPUT_VRPN_TYPE_DESCRIPTION, "vrpn_Analog Channel");
}

static const input_vrpn_desc wand0 = {.tracker = "Tracker0", .buttons = "Wand0"};

static void test_decode_stream(void **state)
{
    static stream s;
    s.n = 0;
    preamble(&s);
    const double head[7] = {0.1, 1.7, -0.2, 0, 0, 0, 1};
    const double h = sqrt(0.5);
    const double wand[7] = {0.3, 1.2, -0.4, 0, 2 * h, 0, 2 * h}; /* unnormalised: 90 deg about Y */
    add_pos_quat(&s, 0, head);
    add_pos_quat(&s, 1, wand);
    add_pos_quat(&s, 7, head);                                  /* another sensor: ignored */
    uint8_t st4[20];
    be32(st4, 4);
    for (int i = 0; i < 4; i++)
        be32(st4 + 4 + 4 * i, i == 3);
    add(&s, 12, 42, st4, sizeof st4);
    uint8_t ch[8];
    be32(ch, 2);
    be32(ch + 4, 1);
    add(&s, 12, 41, ch, sizeof ch);
    add_analog(&s, 2, 0.5, -2.0);                               /* clamped to -1 */

    input_vrpn_session ses = {0};
    input_source_state st = {0};
    char err[256];
    assert_int_equal(input_vrpn_decode(&wand0, &ses, s.b, s.n, &st, 2.5, err, sizeof err), (long)s.n);
    assert_int_equal(ses.dropped, 0);
    assert_int_equal(ses.messages, 6);                          /* sensor 7 is valid, unused */
    assert_true(st.head.valid && st.wand.valid);
    assert_float_equal(st.head.position[0], 0.1f, 0);
    assert_float_equal(st.head.rotation[0], 1.0f, 0);
    assert_float_equal(st.wand.position[2], -0.4f, 0);
    /* 90 degrees about Y: x -> -z, z -> x (column-major) */
    assert_float_equal(st.wand.rotation[2], -1.0f, 1e-6);
    assert_float_equal(st.wand.rotation[6], 1.0f, 1e-6);
    assert_float_equal(st.wand.rotation[4], 1.0f, 1e-6);
    assert_int_equal(st.buttons, (1u << 3) | (1u << 2));
    assert_int_equal(st.pressed, (1u << 3) | (1u << 2));
    assert_float_equal(st.axes[0], 0.5f, 0);
    assert_float_equal(st.axes[1], -1.0f, 0);
    assert_float_equal(st.head.time, 2.5, 0);

    /* Every prefix: only whole messages are consumed, never past the end. */
    for (size_t n = 0; n <= s.n; n++) {
        input_vrpn_session s2 = {0};
        input_source_state st2 = {0};
        uint8_t *copy = malloc(n ? n : 1);
        memcpy(copy, s.b, n);
        long c = input_vrpn_decode(&wand0, &s2, copy, n, &st2, 1.0, err, sizeof err);
        free(copy);
        assert_true(c >= 0 && (size_t)c <= n && c % 8 == 0);
        assert_true(n - (size_t)c < 24 + 64 + 8);
    }
}

static void test_decode_bad_input(void **state)
{
    static stream s;
    char err[256];
    input_vrpn_session ses = {0};
    input_source_state st = {0};
    s.n = 0;
    preamble(&s);
    const double good[7] = {1, 2, 3, 0, 0, 0, 1};
    add_pos_quat(&s, 0, good);
    const double nan_pos[7] = {NAN, 2, 3, 0, 0, 0, 1}, inf_q[7] = {0, 0, 0, INFINITY, 0, 0, 1},
                 zero_q[7] = {5, 5, 5, 0, 0, 0, 0}, huge[7] = {1e300, 0, 0, 0, 0, 0, 1};
    add_pos_quat(&s, 0, nan_pos);
    add_pos_quat(&s, 0, inf_q);
    add_pos_quat(&s, 0, zero_q);
    add_pos_quat(&s, 0, huge);
    add_analog(&s, 2.5, 0.1, 0.1);                 /* non-integer count */
    add_analog(&s, NAN, 0.1, 0.1);
    add_analog(&s, 2, NAN, 0.1);
    add_analog(&s, 3, 0.1, 0.1);                   /* count beyond the body */
    uint8_t short_body[4] = {0};
    add(&s, 11, 40, short_body, 4);                /* truncated Pos_Quat */
    add(&s, 99, 40, short_body, 4);                /* undescribed sender */
    add(&s, 11, 200, short_body, 4);               /* undescribed type */
    uint8_t badname[8];
    be32(badname, 1000);                           /* name length beyond the body */
    add(&s, 13, INPUT_VRPN_SENDER_DESCRIPTION, badname, sizeof badname);
    assert_int_equal(input_vrpn_decode(&wand0, &ses, s.b, s.n, &st, 1.0, err, sizeof err), (long)s.n);
    assert_int_equal(ses.messages, 1);
    assert_int_equal(ses.dropped, 12);
    assert_float_equal(st.head.position[0], 1.0f, 0);     /* the good pose survives */
    assert_float_equal(st.axes_time, 0.0, 0);

    /* A length field outside [24, 64 KiB] means this is not VRPN: drop the connection. */
    uint8_t bad[32] = {0};
    be32(bad, 1u << 20);
    assert_int_equal(input_vrpn_decode(&wand0, &ses, bad, sizeof bad, &st, 1.0, err, sizeof err), -1);
    assert_non_null(strstr(err, "length"));
    be32(bad, 8);
    assert_int_equal(input_vrpn_decode(&wand0, &ses, bad, sizeof bad, &st, 1.0, err, sizeof err), -1);

    uint8_t cookie[24];
    input_vrpn_write_cookie(cookie);
    assert_memory_equal(cookie, "vrpn: ver. 07.35  0\0\0\0\0", 24);
    assert_true(input_vrpn_cookie_ok(cookie));
    memcpy(cookie, "vrpn: ver. 07.99  0", 19);          /* minor version may differ */
    assert_true(input_vrpn_cookie_ok(cookie));
    memcpy(cookie, "vrpn: ver. 08.00  0", 19);
    assert_false(input_vrpn_cookie_ok(cookie));
}

/* ---- real server process ---- */

typedef struct server {
    pid_t pid;
    int port;
} server;

static server server_start(int port, const char *x, const char *flag)
{
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    server sv = {0};
    char portbuf[16];
    snprintf(portbuf, sizeof portbuf, "%d", port);
    sv.pid = fork();
    if (sv.pid == 0) {
        dup2(fds[1], 1);
        close(fds[0]);
        execl(CAVELIGHT_BINARY_DIR "/vrpn_test_server", "vrpn_test_server", "--port", portbuf,
              "--x", x, "--seconds", "20", flag, (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    FILE *f = fdopen(fds[0], "r");
    assert_int_equal(fscanf(f, "port %d", &sv.port), 1);
    fclose(f);
    return sv;
}

static void server_stop(server *sv)
{
    kill(sv->pid, SIGTERM);
    waitpid(sv->pid, NULL, 0);
}

static void sleep_ms(int ms) { nanosleep(&(struct timespec){0, ms * 1000000L}, NULL); }

/* Every line the polls returned (warnings and notices), in order. */
static char said[8192];
static void keep_line(int rc, const char *line)
{
    size_t n = strlen(said);
    if (rc != 0)
        snprintf(said + n, sizeof said - n, "%s\n", line);
}

/* Polls until cond holds or 3 s pass. */
#define POLL_UNTIL(in, st, cond)                                              \
    for (int i_ = 0; i_ < 300; i_++) {                                        \
        keep_line(input_poll(in, &st, err, sizeof err), err);                 \
        if (cond)                                                             \
            break;                                                            \
        sleep_ms(10);                                                         \
    }

static void test_server_and_reconnect(void **state)
{
    char err[256];
    server sv = server_start(0, "0", NULL);
    input *in = input_create(&(input_desc){0}, err, sizeof err);
    input_vrpn_desc d = wand0;
    d.host = "127.0.0.1";
    d.port = sv.port;
    d.reconnect_interval = 0.1;
    input_source *src = input_vrpn_open(&d, err, sizeof err);
    assert_non_null(src);
    input_add_source(in, src, err, sizeof err);
    input_state st;
    said[0] = '\0';
    POLL_UNTIL(in, st, st.head.valid && st.wand.valid && st.axes_time > 0);
    assert_true(input_vrpn_connected(src));
    char want[128];
    snprintf(want, sizeof want, "connected to VRPN server 127.0.0.1:%d (Tracker0)\n", sv.port);
    if (!strstr(said, want))
        fail_msg("no \"%s\" in: %s", want, said);
    assert_float_equal(st.head.position[1], 1.7f, 1e-6);
    assert_float_equal(st.wand.position[0], 0.3f, 1e-6);
    assert_float_equal(st.wand.rotation[2], -1.0f, 1e-6);
    assert_float_equal(st.axes[0], 0.5f, 0);
    assert_float_equal(st.axes[1], -0.25f, 0);
    assert_true(st.buttons & 1u);                         /* from Button States */
    /* button 2 toggles every 10 frames */
    int seen_down = 0;
    for (int i = 0; i < 100 && !seen_down; i++) {
        input_poll(in, &st, err, sizeof err);
        seen_down = (st.pressed >> 2) & 1u;
        sleep_ms(5);
    }
    assert_true(seen_down);

    /* The server goes away: buttons are released, the last pose stays. */
    server_stop(&sv);
    POLL_UNTIL(in, st, !input_vrpn_connected(src));
    assert_false(input_vrpn_connected(src));
    input_poll(in, &st, err, sizeof err);
    assert_int_equal(st.buttons, 0);
    assert_float_equal(st.head.position[0], 0.0f, 0);
    /* It comes back on the same port with the head moved: the client reconnects. */
    server sv2 = server_start(sv.port, "1.5", NULL);
    POLL_UNTIL(in, st, st.head.position[0] == 1.5f);
    assert_float_equal(st.head.position[0], 1.5f, 0);
    assert_int_equal(input_vrpn_connections(src), 2);
    /* connected, lost, connected again: one line each, in that order */
    snprintf(want, sizeof want, "connected to VRPN server 127.0.0.1:%d (Tracker0) again after", sv.port);
    const char *lost = strstr(said, "; retrying every 0.1 s");
    if (!lost || !strstr(lost, want))
        fail_msg("no loss followed by \"%s\" in: %s", want, said);
    server_stop(&sv2);
    input_close(in);
}

static void test_bad_servers(void **state)
{
    char err[256];
    const char *flags[] = {"--bad-cookie", "--oversized"};
    const char *expect[] = {"bad cookie", "message length"};
    for (int k = 0; k < 2; k++) {
        server sv = server_start(0, "0", flags[k]);
        input *in = input_create(&(input_desc){0}, err, sizeof err);
        input_source *src = input_vrpn_open(&(input_vrpn_desc){.name = "cave", .host = "127.0.0.1",
                                                                .port = sv.port,
                                                                .reconnect_interval = 5},
                                            err, sizeof err);
        input_add_source(in, src, err, sizeof err);
        input_state st;
        int rc = 0;
        err[0] = '\0';
        for (int i = 0; i < 300 && rc >= 0; i++) { /* past the notice of a connection */
            rc = input_poll(in, &st, err, sizeof err);
            sleep_ms(10);
        }
        assert_int_equal(rc, -1);
        if (!strstr(err, expect[k]) || !strstr(err, "input cave: VRPN server 127.0.0.1:"))
            fail_msg("\"%s\" lacks \"%s\"", err, expect[k]);
        assert_false(input_vrpn_connected(src));
        /* reported once, not every poll */
        assert_int_equal(input_poll(in, &st, err, sizeof err), 0);
        input_close(in);
        server_stop(&sv);
    }
    /* Nobody listening. */
    server sv = server_start(0, "0", NULL);
    server_stop(&sv);
    input *in = input_create(&(input_desc){0}, err, sizeof err);
    input_add_source(in, input_vrpn_open(&(input_vrpn_desc){.host = "127.0.0.1", .port = sv.port},
                                         err, sizeof err), err, sizeof err);
    input_state st;
    int rc = 0;
    for (int i = 0; i < 100 && rc == 0; i++) {
        rc = input_poll(in, &st, err, sizeof err);
        sleep_ms(5);
    }
    assert_int_equal(rc, -1);
    assert_non_null(strstr(err, "cannot connect"));
    input_close(in);
}

/* The input config names the device the way VRPN users do: "Tracker0@host:port". */
static void test_config(void **state)
{
    char err[256], path[1024], json[512];
    server sv = server_start(0, "0.25", NULL);
    snprintf(path, sizeof path, "%s/test_vrpn_config.json", CAVELIGHT_BINARY_DIR);
    snprintf(json, sizeof json, "{\"sources\": [{\"type\": \"vrpn\", \"name\": \"cave\", "
             "\"tracker\": \"Tracker0@127.0.0.1:%d\", \"button_device\": \"Wand0\", "
             "\"head\": 1, \"wand\": 0, \"buttons\": [\"C\"], \"axes\": [\"Y\", \"X\"]}]}",
             sv.port);
    FILE *f = fopen(path, "wb");
    fputs(json, f);
    fclose(f);
    input *in = input_open(&(input_desc){.path = path}, err, sizeof err);
    if (!in)
        fail_msg("%s", err);
    input_state st;
    POLL_UNTIL(in, st, st.head.valid && st.axes_time > 0 && st.buttons);
    /* sensors swapped by the config: the head is sensor 1 */
    assert_float_equal(st.head.position[0], 0.55f, 1e-6);
    assert_float_equal(st.wand.position[0], 0.25f, 1e-6);
    assert_int_equal(st.buttons, 1u << INPUT_BUTTON_C);
    assert_float_equal(st.axes[INPUT_AXIS_Y], 0.5f, 0);
    assert_float_equal(st.axes[INPUT_AXIS_X], -0.25f, 0);
    input_close(in);
    server_stop(&sv);
    remove(path);
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decode_stream),
        cmocka_unit_test(test_decode_bad_input),
        cmocka_unit_test(test_server_and_reconnect),
        cmocka_unit_test(test_bad_servers),
        cmocka_unit_test(test_config),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
