/* cavelight-bench accuracy reference: only the chart's path-traced reference of one scene
 * (rendered, or read from OUT's cache), and its own noise: the figure that says how sharp
 * the truth is that the chart ranks the methods against (scripts/chart.sh prints it per
 * scene before the sweeps, which then reuse the cached reference). */
#include <math.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"

int accuracy_reference(int argc, char **argv)
{
    acc_options o = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                     .ref_samples = 64};
    const bench_option opts[] = {ACC_COMMON_OPTIONS(&o)};
    int rc = BENCH_PARSE("accuracy reference", "the chart's path-traced reference of one scene "
                         "and its noise (scripts/chart.sh runs it)", opts, argc, argv);
    if (rc != 0)
        return rc > 0 ? 0 : 2;
    acc_setup s;
    if (acc_setup_open(&s, &o) != 0)
        return 1;
    acc_reference ref;
    if (acc_reference_get(&s, &s.base, "a", &ref) != 0) {
        acc_setup_close(&s);
        return 1;
    }
    printf("{\"bench\":\"accuracy\",\"experiment\":\"reference\",\"scene\":\"%s\",\"width\":%d,"
           "\"height\":%d,\"reference_samples\":%d,\"reference_seconds\":%.4g,"
           "\"reference_cached\":%s,\"reference_mean_indirect1\":%.6g,"
           "\"reference_noise_indirect1\":%.6g,\"reference_noise_rel\":%.6g}\n",
           o.scene, o.width, o.height, 2 * ref.samples, ref.seconds,
           ref.cached ? "true" : "false", ref.mean_indirect1, ref.noise_indirect1,
           ref.noise_rel);
    acc_reference_free(&ref);
    acc_setup_close(&s);
    return 0;
}
#else
typedef int accuracy_reference_unused;
#endif
