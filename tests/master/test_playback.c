/* Recording and playback: a recorded session replays to the identical input-state and
 * parameter stream, twice; realtime playback honours the recorded clock; bad files fail
 * with file:line. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "frame/frame_params.h"
#include "input/input.h"
#include "input/input_config.h"
#include "input/input_playback.h"
#include "input/input_source.h"
#include "interaction.h"

enum { POLLS = 240 };

/* A scripted source: the head sways, the wand sweeps, buttons switch layouts and hold C,
 * the axes move; every value depends on the poll count, the times on the real clock. */
typedef struct script_source {
    input_source base;
    int k;
} script_source;

static int script_poll(input_source *s, double now, char *err, size_t errlen)
{
    script_source *sc = (script_source *)s;
    int k = sc->k++;
    float a = 0.05f * (float)k;
    input_pose h = {.valid = 1, .time = now, .position = {0.2f * sinf(a), 1.7f, 0.1f * cosf(a)},
                    .rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    input_pose w = {.valid = 1, .time = now, .position = {0.3f, 1.2f, -0.35f - 0.001f * (float)k},
                    .rotation = {cosf(a), 0, -sinf(a), 0, 1, 0, sinf(a), 0, cosf(a)}};
    s->st.head = h;
    s->st.wand = w;
    uint32_t held = 0;
    if (k % 60 == 10)
        held |= 1u << INPUT_BUTTON_R;         /* next layout every 60 polls */
    if (k % 60 > 20 && k % 60 < 50)
        held |= 1u << INPUT_BUTTON_C;         /* fly / flashlight / GI method */
    if (k % 60 == 30)
        held |= 1u << INPUT_BUTTON_M;
    if (k % 60 == 40)
        held |= 1u << INPUT_BUTTON_AUX;
    input_source_set_buttons(&s->st, held, now);
    float axes[2] = {0.8f * sinf(0.3f * a), -0.6f * cosf(0.2f * a)};
    input_source_set_axes(&s->st, axes, 2, now);
    return 0;
}

static void script_close(input_source *s) { free(s); }

static input_source *script_open(void)
{
    script_source *s = calloc(1, sizeof *s);
    snprintf(s->base.name, sizeof s->base.name, "script");
    s->base.cave_space = 1;
    s->base.poll = script_poll;
    s->base.close = script_close;
    return &s->base;
}

static void params_init(frame_params *p)
{
    memset(p, 0, sizeof *p);
    for (int i = 0; i < 16; i += 5)
        p->head[i] = p->wand[i] = p->navigation[i] = 1.0f;
    p->light_count = 1;
    p->lights[0] = (frame_light){.enabled = 1, .position = {0, 2, 0}, .direction = {0, -1, 0},
                                 .color = {1, 1, 1}, .intensity = 10, .outer_angle = 0.5f,
                                 .inner_angle = 0.4f};
    p->lpv_steps = 8;
    p->absorption = 0.1f;
    p->scattering = 0.2f;
    p->lambda_incr = 0.5f;
    p->hud_layout = 0;
}

/* One entry of the parameter stream: what changed and the resulting parameters. */
typedef struct entry {
    uint32_t changed;
    frame_params p;
} entry;

static void run(input *in, entry *stream, input_state *states, int *n)
{
    char err[256];
    interaction ia_s, *ia = &ia_s;
    interaction_init(ia, &(interaction_desc){0});
    frame_params p;
    params_init(&p);
    *n = 0;
    input_state s;
    memset(&s, 0, sizeof s);
    while (*n < POLLS + 10) {
        assert_int_equal(input_poll(in, &s, err, sizeof err), 0);
        if (s.finished)
            break;
        memcpy(&states[*n], &s, sizeof s);
        stream[*n].changed = interaction_update(ia, &s, s.dt, &p);
        memcpy(&stream[*n].p, &p, sizeof p); /* bytewise: padding included */
        (*n)++;
    }
}

static void test_record_and_replay_twice(void **state)
{
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/test_playback_session.txt", CAVELIGHT_BINARY_DIR);
    static entry live[POLLS + 10], replay[2][POLLS + 10];
    static input_state live_s[POLLS + 10], replay_s[2][POLLS + 10];

    input *in = input_create(&(input_desc){.record_path = path}, err, sizeof err);
    assert_non_null(in);
    assert_int_equal(input_add_source(in, script_open(), err, sizeof err), 0);
    interaction ia_s, *ia = &ia_s;
    interaction_init(ia, &(interaction_desc){0});
    frame_params p;
    params_init(&p);
    uint32_t all = 0;
    for (int i = 0; i < POLLS; i++) {
        assert_int_equal(input_poll(in, &live_s[i], err, sizeof err), 0);
        live[i].changed = interaction_update(ia, &live_s[i], live_s[i].dt, &p);
        memcpy(&live[i].p, &p, sizeof p);
        all |= live[i].changed;
        nanosleep(&(struct timespec){0, 200000}, NULL);
    }
    input_close(in);
    /* The script must have exercised every layout, or the comparison proves little. */
    assert_true(all & INTERACTION_CHANGED_NAVIGATION);
    assert_true(all & INTERACTION_CHANGED_LIGHT);
    assert_true(all & INTERACTION_CHANGED_STEPS);
    assert_true(all & INTERACTION_CHANGED_LAMBDA);
    assert_true(all & INTERACTION_CHANGED_GI);

    for (int r = 0; r < 2; r++) {
        input *pb = input_open(&(input_desc){.path = path}, err, sizeof err);
        if (!pb)
            fail_msg("%s", err);
        int n;
        run(pb, replay[r], replay_s[r], &n);
        input_close(pb);
        assert_int_equal(n, POLLS);
        for (int i = 0; i < n; i++) {
            if (memcmp(&replay_s[r][i], &live_s[i], sizeof live_s[i]) != 0)
                fail_msg("replay %d: input state %d differs from the live one", r, i);
            if (memcmp(&replay[r][i], &live[i], sizeof live[i]) != 0)
                fail_msg("replay %d: parameter update %d differs from the live one", r, i);
        }
    }
    assert_memory_equal(replay[0], replay[1], sizeof replay[0]);
    remove(path);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_realtime_playback(void **state)
{
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/test_playback_rt.txt", CAVELIGHT_BINARY_DIR);
    write_file(path, INPUT_PLAYBACK_MAGIC "\n"
                     "buttons 5 1 1\npoll 5 0\n"
                     "# the second block is due 0.3 s after the first\n"
                     "buttons 5.3 0 0\naxes 5.3 0.5 -0.25 0 0\npoll 5.3 0.3\n");
    input *in = input_create(&(input_desc){0}, err, sizeof err);
    input_source *s = input_playback_open(&(input_playback_desc){.path = path, .realtime = 1},
                                          err, sizeof err);
    assert_non_null(s);
    assert_int_equal(input_add_source(in, s, err, sizeof err), 0);
    input_state st;
    assert_int_equal(input_poll(in, &st, err, sizeof err), 0);
    assert_int_equal(st.buttons, 1);
    assert_int_equal(st.pressed, 1);
    assert_float_equal(st.axes[0], 0.0f, 0);
    nanosleep(&(struct timespec){0, 100000000}, NULL);
    assert_int_equal(input_poll(in, &st, err, sizeof err), 0);
    assert_int_equal(st.buttons, 1);          /* not yet due */
    assert_int_equal(st.pressed, 0);
    nanosleep(&(struct timespec){0, 300000000}, NULL);
    assert_int_equal(input_poll(in, &st, err, sizeof err), 0);
    assert_int_equal(st.buttons, 0);
    assert_float_equal(st.axes[0], 0.5f, 0);
    assert_float_equal(st.axes[1], -0.25f, 0);
    assert_false(st.finished);                /* realtime sources do not drive the clock */
    input_close(in);
    remove(path);
}

static void test_bad_recordings(void **state)
{
    char path[1024], err[256];
    snprintf(path, sizeof path, "%s/test_playback_bad.txt", CAVELIGHT_BINARY_DIR);
    const char *cases[][2] = {
        {INPUT_PLAYBACK_MAGIC "\nhead 1 0 0\npoll 1 0\n", ":2: malformed \"head\""},
        {INPUT_PLAYBACK_MAGIC "\npoll 1 0\nteleport 3\n", ":3: unknown record \"teleport\""},
        {INPUT_PLAYBACK_MAGIC "\naxes 1 nan 0 0 0\npoll 1 0\n", ":2: malformed \"axes\""},
        {INPUT_PLAYBACK_MAGIC "\naxes 1 2 0 0 0\npoll 1 0\n", ":2: malformed \"axes\""},
        {INPUT_PLAYBACK_MAGIC "\nbuttons 1 zz 0\npoll 1 0\n", ":2: malformed \"buttons\""},
        {INPUT_PLAYBACK_MAGIC "\npoll 1 nan\n", ":2: malformed \"poll\""},
        {INPUT_PLAYBACK_MAGIC "\npoll 0 0\npoll 1 -0.5\n", ":3: poll dt -0.5 out of range"},
        {INPUT_PLAYBACK_MAGIC "\npoll 0 0\npoll 0 0\n", ":3: poll dt 0 out of range"},
        {INPUT_PLAYBACK_MAGIC "\npoll 0 1e300\n", ":2: poll dt 1e300 out of range"},
        {INPUT_PLAYBACK_MAGIC "\npoll 0 0.1\n# a comment\npoll 11 10.5\n", ":4: poll dt 10.5 out of range"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_file(path, cases[i][0]);
        input *in = input_open(&(input_desc){.path = path}, err, sizeof err);
        assert_non_null(in);
        input_state st;
        int rc = 0;
        for (int k = 0; k < 3 && rc == 0; k++)
            rc = input_poll(in, &st, err, sizeof err);
        assert_int_equal(rc, -1);
        if (!strstr(err, cases[i][1]) || !strstr(err, path))
            fail_msg("case %zu: \"%s\" lacks \"%s\"", i, err, cases[i][1]);
        assert_true(st.finished);
        assert_true(st.failed);
        input_close(in);
    }
    /* Not a recording, not JSON: one clear line. */
    write_file(path, "hello\n");
    assert_null(input_open(&(input_desc){.path = path}, err, sizeof err));
    assert_non_null(strstr(err, "not a JSON object nor a recording"));
    remove(path);
    assert_null(input_open(&(input_desc){.path = path}, err, sizeof err));
    assert_non_null(strstr(err, "cannot open"));
}

/* The demo's recorded session (configs/input) replays completely and drives every layout;
 * it opens the same way directly and through configs/input/demo.json. */
static void test_sample_session(void **state)
{
    const char *paths[] = {CAVELIGHT_SOURCE_DIR "/configs/input/demo-session.txt",
                           CAVELIGHT_SOURCE_DIR "/configs/input/demo.json"};
    static entry stream[2][POLLS + 10];
    static input_state states[POLLS + 10];
    for (int k = 0; k < 2; k++) {
        char err[256];
        input *in = input_open(&(input_desc){.path = paths[k]}, err, sizeof err);
        if (!in)
            fail_msg("%s", err);
        int n;
        run(in, stream[k], states, &n);
        input_close(in);
        assert_int_equal(n, 150);
        uint32_t all = 0;
        for (int i = 0; i < n; i++)
            all |= stream[k][i].changed;
        const uint32_t want = INTERACTION_CHANGED_HEAD | INTERACTION_CHANGED_WAND |
                              INTERACTION_CHANGED_NAVIGATION | INTERACTION_CHANGED_LIGHT |
                              INTERACTION_CHANGED_STEPS | INTERACTION_CHANGED_ABSORPTION |
                              INTERACTION_CHANGED_LAMBDA | INTERACTION_CHANGED_LAYOUT;
        assert_int_equal(all & want, want);
        const frame_params *last = &stream[k][n - 1].p;
        assert_int_equal(last->hud_layout, INTERACTION_SETTINGS);
        assert_true(last->navigation[14] < -0.3f);             /* flew forward */
        assert_true(last->navigation[8] > 0.2f);  /* turned left: CAVE -Z now points to -X */
        assert_float_equal(last->lights[0].intensity, 20.0f, 1e-3);
        assert_true(last->lights[0].color[2] < 0.9f);          /* tinted */
        assert_int_equal(last->lpv_steps, 9);
        assert_float_equal(last->lambda_incr, 0.8f, 0);
    }
    assert_memory_equal(stream[0], stream[1], sizeof stream[0]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_record_and_replay_twice),
        cmocka_unit_test(test_realtime_playback),
        cmocka_unit_test(test_bad_recordings),
        cmocka_unit_test(test_sample_session),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
