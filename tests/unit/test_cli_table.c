/* cli_parse() with a long table: every option reaches set(), also those whose index is a
 * character getopt_long() returns of itself ('?' 63, ':' 58, 'h' 104), which a table of
 * more than 58 options has (the node's has 70 with four GI methods). Fails when an option's
 * getopt value is its bare index. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "base/cli.h"

enum { OPTIONS = 120 };

static int seen[OPTIONS];

static const char *set(void *user, int id, const char *value)
{
    (void)user;
    seen[id] = value && strcmp(value, "v") == 0;
    return NULL;
}

static void test_every_index_parses(void **state)
{
    (void)state;
    static char names[OPTIONS][8];
    static cli_option rows[OPTIONS];
    static const char *const groups[] = {"options"};
    for (int i = 0; i < OPTIONS; i++) {
        snprintf(names[i], sizeof names[i], "o%d", i);
        rows[i] = (cli_option){.id = i, .name = names[i], .arg = "X", .help = "an option"};
    }
    cli_program p = {.name = "test", .usage = "test", .groups = groups, .group_count = 1,
                     .options = rows, .count = OPTIONS, .set = set};
    for (int i = 0; i < OPTIONS; i++) {
        char flag[16];
        snprintf(flag, sizeof flag, "--o%d", i);
        char *argv[] = {"test", flag, "v", NULL};
        const char *positional[1];
        int npositional;
        cli_given given;
        memset(seen, 0, sizeof seen);
        assert_int_equal(cli_parse(&p, 3, argv, positional, 1, &npositional, &given), CLI_OK);
        if (!seen[i])
            fail_msg("--o%d did not reach set()", i);
        assert_int_equal(given.given[i], 1);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_every_index_parses)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
