/* bench_cli: the benchmarks' command lines through base/cli.h (see bench.h). */
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "gi/gi_settings.h"

enum { SETTING_ID = 1000 }; /* + gi_option index */

typedef struct parse_state {
    const bench_option *opts;
    frame_params *frame; /* BENCH_SETTINGS' */
} parse_state;

static const char *set(void *user, int id, const char *v)
{
    parse_state *st = user;
    if (id >= SETTING_ID)
        return gi_set(st->frame, gi_option_at(id - SETTING_ID)->row->name, v);
    const bench_option *o = &st->opts[id];
    if (o->choices) {
        int k = cli_choice(v, o->choices, o->choice_count);
        if (k < 0)
            return cli_choice_reason(o->choices, o->choice_count);
        *o->value = k;
        return NULL;
    }
    if (o->text) {
        *o->text = v;
        return NULL;
    }
    return cli_int(v, o->lo, o->hi, o->value);
}

/* The defaults are the variables' values before parsing: shown from there. */
static const char *show_default(void *user, int id, char *buf, size_t cap)
{
    const bench_option *o = &((parse_state *)user)->opts[id];
    if (o->choices)
        snprintf(buf, cap, "%s", o->choices[*o->value]);
    else if (o->text)
        snprintf(buf, cap, "%s", *o->text ? *o->text : "none");
    else
        snprintf(buf, cap, "%d", *o->value);
    return buf;
}

int bench_parse(const char *bench, const char *summary, const bench_option *opts, int count,
                int argc, char **argv)
{
    static cli_option table[CLI_MAX_OPTIONS];
    if (count > CLI_MAX_OPTIONS)
        return -1;
    parse_state st = {opts, NULL};
    int rows = 0;
    for (int i = 0; i < count; i++) {
        if (opts[i].frame)
            st.frame = opts[i].frame;
        else
            table[rows++] = (cli_option){.id = i, .name = opts[i].name, .arg = opts[i].arg,
                                         .help = opts[i].help};
    }
    if (st.frame)
        rows = gi_cli_options(table, rows, SETTING_ID, 1, 2, 0);
    static const char *const groups[] = {"Options", "GI settings (cavelight-node's)",
                                         "Display settings (cavelight-node's)"};
    char name[64], usage[512];
    snprintf(name, sizeof name, "cavelight-bench %s", bench);
    snprintf(usage, sizeof usage, "usage: cavelight-bench %s [options]\n  %s\n", bench, summary);
    cli_program p = {.name = name, .usage = usage, .groups = groups, .group_count = 3,
                     .options = table, .count = rows, .set = set, .show_default = show_default,
                     .user = &st};
    int npositional;
    cli_given given;
    switch (cli_parse(&p, argc, argv, NULL, 0, &npositional, &given)) {
    case CLI_OK: return 0;
    case CLI_HELP: return 1;
    default: return -1;
    }
}
