/* gi_cost: the limits a cluster node holds the frames' GI settings to. The runaway
 * frame (lattice 128, 256 steps) and the other heavy combinations are refused, naming what;
 * everything up to ten times the set-up (or default) work passes; heavier settings pass
 * when the config sets the wall up for them; the memory cap counts the method's state and
 * the RSMs; the caches method's VALs and density and the ldm method's photons and maps are bounded
 * likewise; the budget plan's measuring frames are within the defaults' limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "gi/gi_cost.h"
#include "gi/gi_settings.h"
#include "gi/ilpv/ilpv_budget.h"

/* A 6 x 3 x 6 m room and one spot light. */
static gi_limits limits(void)
{
    gi_limits l = {.bounds_min = {-3, 0, -3}, .bounds_max = {3, 3, 3}, .memory_mb = 2048};
    frame_params_default(&l.base);
    return l;
}

static frame_params frame(const char *settings[][2], int n)
{
    frame_params p;
    frame_params_default(&p);
    p.light_count = 1;
    p.lights[0] = (frame_light){.enabled = 1, .intensity = 10, .type = SCENE_LIGHT_SPOT};
    for (int i = 0; i < n; i++)
        assert_null(gi_set(&p, settings[i][0], settings[i][1]));
    return p;
}
#define FRAME(...) frame((const char *[][2]){__VA_ARGS__}, (int)(sizeof((const char *[][2]){__VA_ARGS__}) / sizeof(const char *[2])))

static int within(const gi_limits *l, frame_params p, char *why)
{
    return gi_cost_within(l, &p, why, 256);
}

static void test_ilpv_work(void **state)
{
    gi_limits l = limits();
    char why[256];
    assert_true(within(&l, FRAME({"gi", "ilpv"}), why));
    assert_true(within(&l, FRAME({"lattice", "64"}), why)); /* 8x the cells */
    assert_false(within(&l, FRAME({"lattice", "128"}, {"steps", "256"}), why));
    assert_non_null(strstr(why, "the ilpv settings would take"));
    assert_non_null(strstr(why, "(at most 10)"));
    assert_false(within(&l, FRAME({"lattice", "64"}, {"steps", "16"}), why)); /* about 15x */
    /* Set up for it in the config: the same frame passes. */
    assert_null(gi_set(&l.base, "lattice", "64"));
    assert_null(gi_set(&l.base, "steps", "16"));
    assert_true(within(&l, FRAME({"lattice", "64"}, {"steps", "16"}), why));
    /* A lighter set-up still allows the defaults' tenfold. */
    l = limits();
    assert_null(gi_set(&l.base, "lattice", "8"));
    assert_true(within(&l, FRAME({"lattice", "64"}), why));
}

static void test_vpl_and_rsm_work(void **state)
{
    gi_limits l = limits();
    char why[256];
    assert_true(within(&l, FRAME({"gi", "vpl"}), why));
    assert_false(within(&l, FRAME({"gi", "vpl"}, {"vpl-count", "4096"}), why)); /* 16x the gather */
    assert_non_null(strstr(why, "the vpl settings"));
    assert_true(within(&l, FRAME({"gi", "vpl"}, {"vpl-count", "4096"}, {"vpl-interleave", "4"}), why));
    assert_true(within(&l, FRAME({"rsm", "512"}), why)); /* 4x the texels */
    assert_false(within(&l, FRAME({"rsm", "2048"}), why));
    assert_non_null(strstr(why, "--rsm 2048"));
    assert_true(within(&l, FRAME({"gi", "none"}, {"rsm", "256"}), why)); /* nothing to bound */
}

/* The caches method: more VALs within the tenfold; every RSM texel as a VAL, or caches
 * ten times as dense, beyond it (unless the config sets the wall up for them); glossy
 * proxies count in its memory. */
static void test_caches_work(void **state)
{
    gi_limits l = limits();
    char why[256];
    assert_true(within(&l, FRAME({"gi", "caches"}), why));
    assert_true(within(&l, FRAME({"gi", "caches"}, {"caches-vals", "16384"}), why)); /* 8x */
    assert_false(within(&l, FRAME({"gi", "caches"}, {"caches-selection", "all"}), why));
    assert_non_null(strstr(why, "the caches settings"));
    assert_false(within(&l, FRAME({"gi", "caches"}, {"caches-density", "1000"}), why));
    assert_null(gi_set(&l.base, "caches-selection", "all"));
    assert_true(within(&l, FRAME({"gi", "caches"}, {"caches-selection", "all"}), why));
    /* Glossy proxies: a second proxy per cache and a second 1080p texture (16 floats each). */
    gi_cost off, on;
    frame_params p = FRAME({"gi", "caches"});
    gi_cost_method(&p, l.bounds_min, l.bounds_max, &off);
    p = FRAME({"gi", "caches"}, {"caches-glossy", "on"});
    gi_cost_method(&p, l.bounds_min, l.bounds_max, &on);
    assert_true(on.memory_bytes - off.memory_bytes >= 1920.0 * 1080 * 16);
}

/* The ldm method: more photons within the tenfold, 64 x 64 of them beyond it; the maps'
 * memory counts towards the cap. */
static void test_ldm_cost(void **state)
{
    gi_limits l = limits();
    char why[256];
    assert_true(within(&l, FRAME({"gi", "ldm"}), why));
    assert_true(within(&l, FRAME({"gi", "ldm"}, {"ldm-photons", "64"}), why)); /* 4x */
    assert_false(within(&l, FRAME({"gi", "ldm"}, {"ldm-photons", "64"}, {"ldm-directions", "128"}), why));
    assert_non_null(strstr(why, "the ldm settings"));
    gi_cost m;
    frame_params p = FRAME({"gi", "ldm"}, {"ldm-directions", "64"}, {"ldm-resolution", "256"});
    gi_cost_method(&p, l.bounds_min, l.bounds_max, &m);
    assert_true(m.memory_bytes >= 64.0 * 256 * 256 * p.ldm_layers * 4);
}

static void test_memory(void **state)
{
    gi_limits l = limits();
    char why[256];
    gi_cost m, r;
    frame_params p = FRAME({"lattice", "64"});
    gi_cost_method(&p, l.bounds_min, l.bounds_max, &m);
    gi_cost_rsm(&p, &r);
    assert_true(m.memory_bytes > 64.0 * 32 * 64 * 400); /* every cell's volumes */
    assert_true(r.memory_bytes == 256.0 * 256 * 48);     /* one spot light's view */
    l.memory_mb = (m.memory_bytes + r.memory_bytes) / (1024.0 * 1024.0) * 0.9;
    assert_false(within(&l, p, why));
    assert_non_null(strstr(why, "limits.gi_memory_mb"));
    l.memory_mb *= 1.2;
    assert_true(within(&l, p, why));
    /* A point light renders six views. */
    p.lights[0].type = SCENE_LIGHT_POINT;
    gi_cost_rsm(&p, &r);
    assert_true(r.memory_bytes == 6 * 256.0 * 256 * 48);
}

/* The ambient occlusion's maps count like a method (issue 34: --ao ldm --ao-directions 512
 * --ao-resolution 512 --ldm-layers 32 --ldm-memory 65536 asked GL for 16 GB): their work
 * against the set-up's AO, their memory in the total, whatever ldm-memory says. */
static void test_ao_counted(void **state)
{
    gi_limits l = limits();
    char why[256];
    assert_true(within(&l, FRAME({"ao", "ldm"}), why));
    assert_true(within(&l, FRAME({"ao", "ssao"}), why));
    frame_params heavy = FRAME({"ao", "ldm"}, {"ao-directions", "512"}, {"ao-resolution", "512"},
                               {"ldm-layers", "32"}, {"ldm-memory", "65536"});
    assert_false(within(&l, heavy, why));
    assert_non_null(strstr(why, "--ao ldm with 512 directions of 512^2 texels x 32 layers"));
    /* set up for them in the config: the work passes, the memory does not */
    l.base = heavy;
    assert_false(within(&l, heavy, why));
    assert_non_null(strstr(why, "with its RSMs and AO maps would take 16"));
    assert_non_null(strstr(why, "limits.gi_memory_mb"));
    gi_cost a;
    gi_cost_ao(&heavy, &a);
    assert_true(a.memory_bytes == 512.0 * 512 * 512 * 32 * 4);
    /* a node keeps its last AO settings within the limits */
    frame_params kept = FRAME({"ao", "ldm"});
    gi_cost_keep_settings(&kept, &heavy);
    l = limits();
    assert_true(within(&l, heavy, why));
}

/* The paper transport holds its own volumes: the injection and two for the merge and the
 * steps, 12 floats per cell each; the same work per step. */
static void test_paper_memory(void **state)
{
    gi_limits l = limits();
    gi_cost beams, paper;
    frame_params p = FRAME({"lattice", "64"});
    gi_cost_method(&p, l.bounds_min, l.bounds_max, &beams);
    p = (frame_params)FRAME({"lattice", "64"}, {"lpv-transport", "paper"});
    gi_cost_method(&p, l.bounds_min, l.bounds_max, &paper);
    printf("lattice 64: beams %.1f MB, paper %.1f MB\n", beams.memory_bytes / 1048576.0,
           paper.memory_bytes / 1048576.0);
    assert_true(paper.memory_bytes >= 64.0 * 32 * 64 * 3 * 12 * 4);
    assert_true(paper.memory_bytes < beams.memory_bytes);
    assert_true(paper.work == beams.work);
}

static void test_budget_plan_within(void **state)
{
    gi_limits l = limits();
    char why[256];
    ilpv_budget_plan plan;
    frame_params base = FRAME({"gi", "ilpv"});
    ilpv_budget_plan_init(&plan, &base, l.bounds_min, l.bounds_max);
    for (int i = 0; i < ILPV_BUDGET_FRAMES; i++) {
        frame_params f;
        ilpv_budget_plan_frame(&plan, i, &f);
        assert_true(within(&l, f, why));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ilpv_work),
        cmocka_unit_test(test_vpl_and_rsm_work),
        cmocka_unit_test(test_caches_work),
        cmocka_unit_test(test_ldm_cost),
        cmocka_unit_test(test_memory),
        cmocka_unit_test(test_ao_counted),
        cmocka_unit_test(test_paper_memory),
        cmocka_unit_test(test_budget_plan_within),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
