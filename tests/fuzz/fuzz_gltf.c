/* libFuzzer target: any bytes as a scene file through scene_load() (the glTF importer and
 * scene_finish). Bytes that start with the GLB magic are a .glb, others a .gltf. The file
 * lives in a private temporary folder, so relative uris in the input resolve to the input
 * itself or to nothing. Built like fuzz_dtrack, with clang++ for the importer. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[64], gltf_path[96], glb_path[96];

static void cleanup(void)
{
    unlink(gltf_path);
    unlink(glb_path);
    rmdir(dir);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "%s/cavelight-fuzz-gltf-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
        if (!mkdtemp(dir))
            abort();
        snprintf(gltf_path, sizeof gltf_path, "%s/in.gltf", dir);
        snprintf(glb_path, sizeof glb_path, "%s/in.glb", dir);
        atexit(cleanup);
    }
    const char *path = size >= 4 && memcmp(data, "glTF", 4) == 0 ? glb_path : gltf_path;
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        abort();
    scene s;
    char err[512];
    err[0] = 0;
    if (scene_load(path, &s, err, sizeof err) == 0) {
        if (s.triangle_count == 0)
            abort();
        for (size_t i = 0; i < 9 * s.triangle_count; i++)
            if (!isfinite(s.positions[i]))
                abort();
        for (size_t t = 0; t < s.triangle_count; t++)
            if (s.triangle_material[t] >= s.material_count)
                abort();
        for (size_t m = 0; m < s.material_count; m++)
            if (s.materials[m].base_color_texture >= (int)s.texture_count)
                abort();
        if (strchr(s.warning, '\n'))
            abort(); /* a warning is one line */
        scene_free(&s);
    } else if (!err[0] || strchr(err, '\n')) {
        abort(); /* a refusal is one line */
    }
    return 0;
}
