/* cli: a table as long as CLI_MAX_OPTIONS parses every option as itself, whatever its
 * place: the 59th, 64th and 105th options are not taken for getopt's ':', '?' and 'h'
 * (the 64th was refused as unknown, "--ao: did you mean --ao?", before). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "base/cli.h"

static int seen[CLI_MAX_OPTIONS];

static const char *set(void *user, int id, const char *value)
{
    (void)user;
    (void)value;
    seen[id - 1000]++;
    return NULL;
}

static void test_every_place_parses(void **state)
{
    (void)state;
    static cli_option rows[CLI_MAX_OPTIONS];
    static char names[CLI_MAX_OPTIONS][8];
    for (int i = 0; i < CLI_MAX_OPTIONS; i++) {
        snprintf(names[i], sizeof names[i], "o%d", i);
        rows[i] = (cli_option){1000 + i, names[i], NULL, NULL, 0, 0, "an option"};
    }
    static const char *const groups[] = {"Options"};
    cli_program p = {.name = "test", .usage = "", .groups = groups, .group_count = 1,
                     .options = rows, .count = CLI_MAX_OPTIONS, .set = set};
    for (int i = 0; i < CLI_MAX_OPTIONS; i++) {
        char arg[16];
        snprintf(arg, sizeof arg, "--o%d", i);
        char *argv[] = {"test", arg, NULL};
        const char *positional[1];
        int npos;
        cli_given given;
        memset(seen, 0, sizeof seen);
        assert_int_equal(cli_parse(&p, 2, argv, positional, 1, &npos, &given), CLI_OK);
        assert_int_equal(seen[i], 1);
        assert_int_equal(given.given[i], 1);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_every_place_parses)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
