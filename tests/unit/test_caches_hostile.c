/* The light caches against hostile input: a scene of huge extent (refused at load, and a
 * placement of unbounded point count refused rather than overflowing), and a cache folder
 * others can write (names planted for the writer's temporary, a folder writable by all, a
 * FIFO where the file goes). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gi/caches/cache_file.h"
#include "gi/caches/cache_place.h"

static char dir[300];

static int setup_dir(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "%s/test_caches_hostile.%ld", CAVELIGHT_BINARY_DIR, (long)getpid());
    return mkdir(dir, 0700);
}

static int teardown_dir(void **state)
{
    (void)state;
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* One quad of side `side` at height y, material 0. */
static void quad(scene *s, float side, float y)
{
    memset(s, 0, sizeof *s);
    scene_material m = {{0.8f, 0.8f, 0.8f, 1}, -1, {0, 0, 0}, 1};
    assert_true(scene_add_material(s, &m) >= 0);
    const float a[3] = {0, y, 0}, b[3] = {side, y, 0}, c[3] = {side, y, side},
                d[3] = {0, y, side}, n[3] = {0, 1, 0};
    assert_int_equal(scene_add_quad(s, a, b, c, d, n, 0), 0);
}

static void test_extent_refused(void **state)
{
    (void)state;
    const float sides[] = {1e20f, 1e10f, 2e5f};
    for (int i = 0; i < 3; i++) {
        scene s;
        char err[300] = "";
        quad(&s, sides[i], 0);
        assert_int_equal(scene_finish(&s, err, sizeof err), -1);
        print_message("%s\n", err);
        assert_non_null(strstr(err, "limit of 100000 m"));
        scene_free(&s);
    }
    scene s;
    char err[300] = "";
    quad(&s, 1e4f, 0);
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    scene_free(&s);
}

/* A triangle whose area overflows a float, past scene_finish()'s check (a caller that
 * builds bounds itself): each triangle's point count saturates and the sum is refused. */
static void test_unbounded_points_refused(void **state)
{
    (void)state;
    scene s;
    quad(&s, 1e20f, 0);
    for (int a = 0; a < 3; a++)
        s.bounds_min[a] = 0, s.bounds_max[a] = a == 1 ? 0 : 1e20f;
    cache_place_desc d = {1.0f, 0.5f};
    cache_set set;
    char err[300] = "";
    assert_int_equal(cache_place(&s, &d, &set, err, sizeof err), -1);
    print_message("%s\n", err);
    assert_non_null(strstr(err, "over the limit of 16777216"));
    scene_free(&s);
}

static int get(const scene *s, cache_store_report *rep)
{
    cache_place_desc d = {cache_place_edge(s, 4), 0.5f};
    cache_set set;
    char err[256];
    assert_int_equal(cache_store_get(s, &d, dir, &set, rep, err, sizeof err), 0);
    assert_true(set.count > 0);
    cache_set_free(&set);
    if (rep->note[0])
        print_message("note: %s\n", rep->note);
    return rep->from_file;
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* A symlink planted under the temporary name a writer could pick from its pid points at a
 * file outside the folder: it stays as it was. */
static void test_planted_temporary(void **state)
{
    (void)state;
    scene s;
    quad(&s, 4, 0);
    cache_place_desc d = {cache_place_edge(&s, 4), 0.5f};
    cache_key key = cache_key_of(&s, &d);
    char path[600], victim[600], link[700];
    cache_file_path(dir, &key, path, sizeof path);
    snprintf(victim, sizeof victim, "%s.victim", dir);
    FILE *f = fopen(victim, "w");
    assert_non_null(f);
    fputs("precious bytes\n", f);
    fclose(f);
    snprintf(link, sizeof link, "%s.%ld.tmp", path, (long)getpid());
    assert_int_equal(symlink(victim, link), 0);
    cache_store_report rep;
    assert_int_equal(get(&s, &rep), 0);
    assert_int_equal(file_size(victim), 15);
    assert_true(file_size(path) > 15); /* written under its own name */
    assert_int_equal(get(&s, &rep), 1);
    unlink(victim);
    scene_free(&s);
}

/* A folder writable by all without the sticky bit is neither read nor written. */
static void test_open_folder_skipped(void **state)
{
    (void)state;
    scene s;
    quad(&s, 4, 0);
    cache_place_desc d = {cache_place_edge(&s, 4), 0.5f};
    cache_key key = cache_key_of(&s, &d);
    char path[600];
    cache_file_path(dir, &key, path, sizeof path);
    assert_int_equal(chmod(dir, 0777), 0);
    cache_store_report rep;
    assert_int_equal(get(&s, &rep), 0);
    assert_non_null(strstr(rep.note, "writable by all without the sticky bit"));
    assert_null(strchr(rep.note, '\n'));
    assert_int_equal(file_size(path), -1);
    assert_int_equal(chmod(dir, 01777), 0); /* as /tmp: used */
    assert_int_equal(get(&s, &rep), 0);
    assert_string_equal(rep.note, "");
    assert_int_equal(get(&s, &rep), 1);
    assert_int_equal(chmod(dir, 0700), 0);
    scene_free(&s);
}

/* A FIFO named as the cache file: refused at once (the alarm ends a blocked open), placed
 * again and replaced by the file. */
static void test_fifo_cache(void **state)
{
    (void)state;
    scene s;
    quad(&s, 4, 0);
    cache_place_desc d = {cache_place_edge(&s, 4), 0.5f};
    cache_key key = cache_key_of(&s, &d);
    char path[600];
    cache_file_path(dir, &key, path, sizeof path);
    assert_int_equal(mkfifo(path, 0600), 0);
    alarm(30);
    cache_store_report rep;
    assert_int_equal(get(&s, &rep), 0);
    alarm(0);
    assert_non_null(strstr(rep.note, "not a regular file (a FIFO)"));
    assert_int_equal(get(&s, &rep), 1);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_extent_refused),
        cmocka_unit_test(test_unbounded_points_refused),
        cmocka_unit_test_setup_teardown(test_planted_temporary, setup_dir, teardown_dir),
        cmocka_unit_test_setup_teardown(test_open_folder_skipped, setup_dir, teardown_dir),
        cmocka_unit_test_setup_teardown(test_fifo_cache, setup_dir, teardown_dir),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
