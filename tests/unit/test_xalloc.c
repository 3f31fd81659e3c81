/* xalloc: ordinary sizes work; an impossible one ends the process with status 1 and one
 * line on stderr (run in a child process). */
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cmocka.h>

#include "base/xalloc.h"

#if defined(__SANITIZE_ADDRESS__)
/* The test needs malloc to fail, as without ASan, not ASan to stop at the size. */
const char *__asan_default_options(void);
const char *__asan_default_options(void) { return "allocator_may_return_null=1"; }
#endif

static void test_ordinary(void **state)
{
    int *a = xcalloc(16, sizeof *a);
    for (int i = 0; i < 16; i++)
        assert_int_equal(a[i], 0);
    a = xrealloc(a, 1024 * sizeof *a);
    a[1023] = 7;
    char *b = xmalloc(3);
    memcpy(b, "ok", 3);
    assert_string_equal(b, "ok");
    free(a);
    free(b);
}

/* Runs fn in a child with stderr into a pipe; returns its exit status and first line. */
static int child(void (*fn)(void), char *line, size_t cap)
{
    int fd[2];
    assert_int_equal(pipe(fd), 0);
    pid_t pid = fork();
    if (pid == 0) {
        dup2(fd[1], 2);
        fn();
        _exit(0);
    }
    close(fd[1]);
    size_t used = 0;
    for (ssize_t n; used < cap - 1 && (n = read(fd[0], line + used, cap - 1 - used)) > 0;)
        used += (size_t)n;
    line[used] = 0;
    close(fd[0]);
    int st;
    waitpid(pid, &st, 0);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void huge_malloc(void) { free(xmalloc(SIZE_MAX - 4096)); }
static void huge_calloc(void) { free(xcalloc(SIZE_MAX / 2, 4)); }

static void test_out_of_memory_exits_with_one_line(void **state)
{
    void (*fns[2])(void) = {huge_malloc, huge_calloc};
    for (int i = 0; i < 2; i++) {
        char line[8192];
        assert_int_equal(child(fns[i], line, sizeof line), 1);
        char *ours = strstr(line, "cavelight: out of memory");
        assert_non_null(ours);
        char *nl = strchr(ours, '\n');
        assert_non_null(nl);
#if !defined(__SANITIZE_ADDRESS__) /* ASan adds a warning line of its own */
        assert_ptr_equal(ours, line);
        assert_int_equal(nl[1], 0);
#endif
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ordinary),
        cmocka_unit_test(test_out_of_memory_exits_with_one_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
