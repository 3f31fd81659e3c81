/* textfile: whole-file reads, NUL termination and one-line errors without the path. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "base/textfile.h"

static void test_reads_whole_file(void **state)
{
    char path[] = "/tmp/cavelight_textfile_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    const char data[] = "line one\nwith\0nul\n"; /* sizeof includes a final NUL too */
    assert_int_equal(write(fd, data, sizeof data - 1), (ssize_t)(sizeof data - 1));
    close(fd);
    size_t len = 0;
    char err[128] = "";
    char *s = textfile_read(path, &len, err, sizeof err);
    unlink(path);
    assert_non_null(s);
    assert_int_equal(len, sizeof data - 1);
    assert_memory_equal(s, data, sizeof data); /* content plus the added NUL */
    free(s);
}

/* A file over the caller's cap is refused from its size, before it is read. */
static void test_cap(void **state)
{
    (void)state;
    char path[] = "/tmp/cavelight_textfile_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "0123456789", 10), 10);
    close(fd);
    char err[128] = "";
    size_t len = 0;
    assert_null(textfile_read_max(path, 9, &len, err, sizeof err));
    assert_string_equal(err, "10 bytes, more than the 9 a file of its kind may hold");
    char *s = textfile_read_max(path, 10, &len, err, sizeof err);
    unlink(path);
    assert_non_null(s);
    assert_int_equal(len, 10);
    free(s);
}

static void test_empty_file(void **state)
{
    char path[] = "/tmp/cavelight_textfile_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    size_t len = 99;
    char err[128];
    char *s = textfile_read(path, &len, err, sizeof err);
    unlink(path);
    assert_non_null(s);
    assert_int_equal(len, 0);
    assert_int_equal(s[0], '\0');
    free(s);
}

static void test_errors(void **state)
{
    char err[128] = "";
    assert_null(textfile_read("/nonexistent/cavelight.json", NULL, err, sizeof err));
    assert_non_null(strstr(err, "cannot open"));
    assert_null(strstr(err, "/nonexistent")); /* the caller adds the path */
    err[0] = '\0';
    assert_null(textfile_read("/tmp", NULL, err, sizeof err));
    assert_string_equal(err, "not a regular file (a folder)");
}

/* A FIFO with no writer is refused at once (a blocking open would wait for one forever:
 * the alarm ends the test then). */
static void test_fifo(void **state)
{
    (void)state;
    char path[] = CAVELIGHT_BINARY_DIR "/test_textfile_fifo";
    unlink(path);
    assert_int_equal(mkfifo(path, 0600), 0);
    alarm(20);
    char err[128] = "";
    assert_null(textfile_read(path, NULL, err, sizeof err));
    alarm(0);
    unlink(path);
    assert_string_equal(err, "not a regular file (a FIFO)");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reads_whole_file),
        cmocka_unit_test(test_empty_file),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_fifo),
        cmocka_unit_test(test_cap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
