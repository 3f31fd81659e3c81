#include "base/cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* getopt_long's value for option i is FIRST_ID + i: above every character it returns
 * itself ('?', ':', 'h'), which the 64th option's bare index would be. */
enum { HELP_ID = -1000, FIRST_ID = 256, HELP_COLUMN = 30, HELP_WIDTH = 96 };

static const cli_option *by_id(const cli_program *p, int id, int *index)
{
    for (int i = 0; i < p->count; i++)
        if (p->options[i].id == id) {
            if (index)
                *index = i;
            return &p->options[i];
        }
    return NULL;
}

/* Edit distance with a swap of two neighbours counted as one edit (optimal string
 * alignment), for "did you mean": "cuont" is one slip from "count". */
static int distance(const char *a, const char *b)
{
    enum { MAX = 64 };
    int la = (int)strlen(a), lb = (int)strlen(b);
    if (la >= MAX || lb >= MAX)
        return MAX;
    int d[MAX + 1][MAX + 1];
    for (int i = 0; i <= la; i++)
        d[i][0] = i;
    for (int j = 0; j <= lb; j++)
        d[0][j] = j;
    for (int i = 1; i <= la; i++)
        for (int j = 1; j <= lb; j++) {
            int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if (d[i - 1][j] + 1 < best)
                best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[la][lb];
}

static size_t common_start(const char *a, const char *b)
{
    size_t i = 0;
    while (a[i] && a[i] == b[i])
        i++;
    return i;
}

const char *cli_nearest(const char *word, const char *const *candidates, int n)
{
    const char *best = NULL;
    int best_d = 1 << 30, len = (int)strlen(word);
    for (int i = 0; i < n; i++) {
        int d = distance(word, candidates[i]);
        /* A name typed too long ("--framesx") is close. */
        if (strncmp(candidates[i], word, strlen(candidates[i])) == 0)
            d = d < 1 ? d : 1;
        /* A tie goes to the longer common start: slips come late in a word more often
         * ("scren" is "screens", not "scene"). */
        if (d < best_d || (d == best_d && common_start(word, candidates[i]) > common_start(word, best))) {
            best_d = d;
            best = candidates[i];
        }
    }
    int limit = len <= 3 ? 1 : len / 3 > 2 ? len / 3 : 2;
    return best_d <= limit ? best : NULL;
}

const char *cli_closest(const cli_program *p, const char *name)
{
    const char *names[CLI_MAX_OPTIONS + 1];
    int n = 0;
    for (int i = 0; i < p->count && n < CLI_MAX_OPTIONS; i++)
        names[n++] = p->options[i].name;
    names[n++] = "help";
    return cli_nearest(name, names, n);
}

static void refuse_unknown(const cli_program *p, const char *arg)
{
    const char *name = arg;
    while (*name == '-')
        name++;
    char bare[64];
    snprintf(bare, sizeof bare, "%.*s", (int)strcspn(name, "="), name);
    const char *close = cli_closest(p, bare);
    if (close)
        fprintf(stderr, "%s: unknown option %s: did you mean --%s? (see --help)\n", p->name, arg,
                close);
    else
        fprintf(stderr, "%s: unknown option %s (see --help)\n", p->name, arg);
}

cli_result cli_parse(const cli_program *p, int argc, char **argv, const char **positional,
                     int max_positional, int *npositional, cli_given *given)
{
    if (p->count > CLI_MAX_OPTIONS) {
        fprintf(stderr, "%s: more than %d options in the table\n", p->name, CLI_MAX_OPTIONS);
        return CLI_ERROR;
    }
    struct option longs[CLI_MAX_OPTIONS + 2];
    for (int i = 0; i < p->count; i++)
        longs[i] = (struct option){p->options[i].name, p->options[i].arg ? required_argument : no_argument,
                                   NULL, FIRST_ID + i};
    longs[p->count] = (struct option){"help", no_argument, NULL, HELP_ID};
    longs[p->count + 1] = (struct option){0, 0, 0, 0};
    memset(given, 0, sizeof *given);
    opterr = 0;
    optind = 0; /* glibc: start over, so that a program (or a test) may parse twice */
    *npositional = 0;
    for (;;) {
        int index = -1, word = optind ? optind : 1;
        /* "+": no permutation, so that argv[word] is the option being read; positional
         * arguments are taken here, wherever they stand. */
        int c = getopt_long(argc, argv, "+:h", longs, &index);
        if (c == -1) {
            if (optind >= argc)
                break;
            int dashes = optind == word + 1 && strcmp(argv[word], "--") == 0;
            do {
                if (*npositional == max_positional) {
                    fprintf(stderr, "%s: unexpected argument '%s' (options start with --; see --help)\n",
                            p->name, argv[optind]);
                    return CLI_ERROR;
                }
                positional[(*npositional)++] = argv[optind++];
            } while (dashes && optind < argc);
            if (dashes)
                break;
            continue;
        }
        const char *arg = argv[word];
        if (c == 'h' || c == HELP_ID) {
            cli_help(p, stdout);
            return CLI_HELP;
        }
        if (c == ':') {
            const cli_option *o = NULL;
            for (int i = 0; i < p->count && !o; i++)
                if (strcmp(arg + 2, p->options[i].name) == 0)
                    o = &p->options[i];
            fprintf(stderr, "%s: %s needs a value%s%s (see --help)\n", p->name, arg,
                    o && o->arg ? ": " : "", o && o->arg ? o->arg : "");
            return CLI_ERROR;
        }
        if (c == '?') {
            /* An unknown long option, or a short one: "-name" is refused whole rather
             * than as the options n, a, m, e. */
            refuse_unknown(p, arg);
            return CLI_ERROR;
        }
        c -= FIRST_ID;
        if (c < 0 || c >= p->count)
            continue;
        const cli_option *o = &p->options[c];
        /* No abbreviations: an option added later must not change what "--fr" meant. */
        if (strncmp(arg, "--", 2) != 0 || strncmp(arg + 2, o->name, strlen(o->name)) != 0 ||
            (arg[2 + strlen(o->name)] != 0 && arg[2 + strlen(o->name)] != '=')) {
            refuse_unknown(p, arg);
            return CLI_ERROR;
        }
        given->given[c] = 1;
        const char *why = p->set(p->user, o->id, o->arg ? optarg : NULL);
        if (why) {
            fprintf(stderr, "%s: --%s %s: expected %s (see --help)\n", p->name, o->name,
                    optarg ? optarg : "", why);
            return CLI_ERROR;
        }
    }
    return CLI_OK;
}

cli_result cli_check_modes(const cli_program *p, const cli_given *given, int mode)
{
    for (int i = 0; i < p->count; i++) {
        const cli_option *o = &p->options[i];
        if (!given->given[i] || !o->modes || (o->modes >> mode & 1u))
            continue;
        char where[256] = "";
        for (int m = 0; m < p->mode_count; m++)
            if (o->modes >> m & 1u)
                snprintf(where + strlen(where), sizeof where - strlen(where), "%s%s",
                         where[0] ? " or " : "", p->modes[m]);
        fprintf(stderr, "%s: --%s works only in %s, not in %s (see --help)\n", p->name, o->name,
                where, mode < p->mode_count ? p->modes[mode] : "this mode");
        return CLI_ERROR;
    }
    return CLI_OK;
}

const cli_option *cli_find(const cli_program *p, int id)
{
    return by_id(p, id, NULL);
}

int cli_was_given(const cli_program *p, const cli_given *given, int id)
{
    int index;
    return by_id(p, id, &index) && given->given[index];
}

void cli_help(const cli_program *p, FILE *f)
{
    fprintf(f, "%s", p->usage);
    for (int g = 0; g < p->group_count; g++) {
        int any = 0;
        for (int i = 0; i < p->count; i++) {
            const cli_option *o = &p->options[i];
            if (o->group != g)
                continue;
            if (!any)
                fprintf(f, "\n%s:\n", p->groups[g]);
            any = 1;
            char head[160];
            snprintf(head, sizeof head, "  --%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
            int col = (int)strlen(head);
            fputs(head, f);
            if (col >= HELP_COLUMN - 1) { /* a long argument: the help starts below it */
                fputc('\n', f);
                col = 0;
            }
            for (const char *h = o->help; *h;) {
                int n = (int)strcspn(h, "\n");
                fprintf(f, "%*s%.*s", HELP_COLUMN - col, "", n, h);
                col = HELP_COLUMN + n;
                h += n;
                if (*h == '\n') {
                    fputc('\n', f);
                    h++;
                    col = 0;
                }
            }
            char buf[64];
            const char *def = o->def ? o->def :
                              p->show_default ? p->show_default(p->user, o->id, buf, sizeof buf) : NULL;
            if (def && col + (int)strlen(def) + 12 > HELP_WIDTH)
                fprintf(f, "\n%*s(default: %s)", HELP_COLUMN, "", def);
            else if (def)
                fprintf(f, " (default: %s)", def);
            fputc('\n', f);
        }
    }
    fprintf(f, "\nGeneral:\n  --help, -h%*sthis text\n", HELP_COLUMN - 12, "");
    if (p->epilogue)
        fprintf(f, "\n%s", p->epilogue);
}

void cli_option_from_setting(const setting *s, int id, int group, unsigned modes,
                             cli_setting_text *text, cli_option *out)
{
    setting_arg(s, text->arg, sizeof text->arg);
    setting_format(s, setting_default(s), text->def, sizeof text->def);
    *out = (cli_option){id, s->name, text->arg, text->def, group, modes, s->help};
}

const char *cli_int(const char *s, int lo, int hi, int *out)
{
    static char why[64];
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    snprintf(why, sizeof why, "a whole number in %d..%d", lo, hi);
    if (end == s || *end || errno || v < lo || v > hi)
        return why;
    *out = (int)v;
    return NULL;
}

const char *cli_float(const char *s, float lo, float hi, float *out)
{
    static char why[64];
    char *end;
    errno = 0;
    float v = strtof(s, &end);
    snprintf(why, sizeof why, "a number in [%g, %g]", lo, hi);
    if (end == s || *end || errno || !isfinite(v) || v < lo || v > hi)
        return why;
    *out = v;
    return NULL;
}

const char *cli_floats(const char *s, int n, float *out)
{
    static char why[64];
    snprintf(why, sizeof why, "%d comma-separated numbers", n);
    for (int i = 0; i < n; i++) {
        char *end;
        errno = 0;
        float v = strtof(s, &end);
        if (end == s || errno || !isfinite(v))
            return why;
        out[i] = v;
        s = end;
        if (i + 1 < n) {
            if (*s != ',')
                return why;
            s++;
        }
    }
    return *s ? why : NULL;
}

int cli_choice(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (strcmp(s, names[i]) == 0)
            return i;
    return -1;
}

const char *cli_choice_reason(const char *const *names, int n)
{
    static char why[256];
    snprintf(why, sizeof why, "one of ");
    for (int i = 0; i < n; i++)
        snprintf(why + strlen(why), sizeof why - strlen(why), "%s%s", i ? (i + 1 == n ? " or " : ", ") : "",
                 names[i]);
    return why;
}
