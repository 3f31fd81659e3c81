// gltf_import: glTF 2.0 (.gltf, .glb) into the C scene model, through tinygltf.
// The one C++ file of the project: everything C++ stays in here behind gltf_import().
// Reads meshes (TRIANGLES), node transforms, base colour factor and texture, emissive
// factor (times KHR_materials_emissive_strength) and KHR_lights_punctual spot lights.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <strings.h>
#include <vector>

extern "C" {
#include "scene/scene.h"
}

namespace {

struct mat4 {
    double m[16]; // column-major
};

mat4 identity()
{
    mat4 r{};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
    return r;
}

mat4 mul(const mat4 &a, const mat4 &b)
{
    mat4 r{};
    for (int c = 0; c < 4; c++)
        for (int rr = 0; rr < 4; rr++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a.m[k * 4 + rr] * b.m[c * 4 + k];
            r.m[c * 4 + rr] = s;
        }
    return r;
}

mat4 node_local(const tinygltf::Node &n)
{
    if (n.matrix.size() == 16) {
        mat4 r;
        for (int i = 0; i < 16; i++)
            r.m[i] = n.matrix[i];
        return r;
    }
    mat4 t = identity(), rot = identity(), s = identity();
    if (n.translation.size() == 3)
        for (int i = 0; i < 3; i++)
            t.m[12 + i] = n.translation[i];
    if (n.rotation.size() == 4) {
        double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        rot.m[0] = 1 - 2 * (y * y + z * z); rot.m[1] = 2 * (x * y + z * w); rot.m[2] = 2 * (x * z - y * w);
        rot.m[4] = 2 * (x * y - z * w); rot.m[5] = 1 - 2 * (x * x + z * z); rot.m[6] = 2 * (y * z + x * w);
        rot.m[8] = 2 * (x * z + y * w); rot.m[9] = 2 * (y * z - x * w); rot.m[10] = 1 - 2 * (x * x + y * y);
    }
    if (n.scale.size() == 3)
        for (int i = 0; i < 3; i++)
            s.m[i * 5] = n.scale[i];
    return mul(t, mul(rot, s));
}

void transform_point(const mat4 &m, const float in[3], float out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = (float)(m.m[r] * in[0] + m.m[4 + r] * in[1] + m.m[8 + r] * in[2] + m.m[12 + r]);
}

// Normals go through the inverse transpose of the upper 3x3 (the cofactor matrix is
// proportional to it, and the scene normalizes afterwards).
void transform_normal(const mat4 &m, const float in[3], float out[3])
{
    const double *a = m.m;
    double c[9] = {
        a[5] * a[10] - a[6] * a[9], a[6] * a[8] - a[4] * a[10], a[4] * a[9] - a[5] * a[8],
        a[9] * a[2] - a[10] * a[1], a[10] * a[0] - a[8] * a[2], a[8] * a[1] - a[9] * a[0],
        a[1] * a[6] - a[2] * a[5], a[2] * a[4] - a[0] * a[6], a[0] * a[5] - a[1] * a[4],
    };
    // c[3*col + row] is the cofactor of element (row, col) of the column-major 3x3.
    for (int r = 0; r < 3; r++)
        out[r] = (float)(c[r] * in[0] + c[3 + r] * in[1] + c[6 + r] * in[2]);
}

struct importer {
    const tinygltf::Model &model;
    scene *out;
    std::string error;
    int material_base;
    int default_material;

    // Float accessor element i, component k; false if the accessor is not float or short.
    bool read_float(int accessor, size_t i, int comps, float *v)
    {
        const tinygltf::Accessor &a = model.accessors[accessor];
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.bufferView < 0 ||
            i >= a.count)
            return false;
        const tinygltf::BufferView &bv = model.bufferViews[a.bufferView];
        size_t stride = a.ByteStride(bv);
        size_t off = bv.byteOffset + a.byteOffset + i * stride;
        const std::vector<unsigned char> &data = model.buffers[bv.buffer].data;
        if (stride == (size_t)-1 || off + comps * sizeof(float) > data.size())
            return false;
        std::memcpy(v, data.data() + off, comps * sizeof(float));
        return true;
    }

    bool read_index(int accessor, size_t i, uint32_t *v)
    {
        const tinygltf::Accessor &a = model.accessors[accessor];
        if (a.bufferView < 0 || i >= a.count)
            return false;
        const tinygltf::BufferView &bv = model.bufferViews[a.bufferView];
        int size = tinygltf::GetComponentSizeInBytes(a.componentType);
        size_t stride = bv.byteStride ? bv.byteStride : (size_t)size;
        size_t off = bv.byteOffset + a.byteOffset + i * stride;
        const std::vector<unsigned char> &data = model.buffers[bv.buffer].data;
        if (size <= 0 || off + size > data.size())
            return false;
        const unsigned char *p = data.data() + off;
        switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: *v = p[0]; return true;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t s; std::memcpy(&s, p, 2); *v = s; return true;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(v, p, 4); return true;
        default: return false;
        }
    }

    bool primitive(const tinygltf::Primitive &prim, const mat4 &world, const std::string &mesh)
    {
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
            return true; // points and lines carry no surfaces: skipped
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) {
            error = "mesh \"" + mesh + "\" has a primitive without POSITION";
            return false;
        }
        auto nrm = prim.attributes.find("NORMAL");
        auto tex = prim.attributes.find("TEXCOORD_0");
        const tinygltf::Accessor &pa = model.accessors[pos->second];
        size_t count = prim.indices >= 0 ? model.accessors[prim.indices].count : pa.count;
        uint32_t material = prim.material >= 0 ? (uint32_t)(material_base + prim.material)
                                               : (uint32_t)default_material;
        for (size_t t = 0; t + 2 < count; t += 3) {
            float p[9], n[9], uv[6];
            bool have_n = nrm != prim.attributes.end(), have_uv = tex != prim.attributes.end();
            for (int k = 0; k < 3; k++) {
                uint32_t idx = (uint32_t)(t + k);
                if (prim.indices >= 0 && !read_index(prim.indices, t + k, &idx)) {
                    error = "mesh \"" + mesh + "\": unreadable index accessor";
                    return false;
                }
                float v[3];
                if (!read_float(pos->second, idx, 3, v)) {
                    error = "mesh \"" + mesh + "\": POSITION is not a readable float VEC3 "
                            "accessor (index " + std::to_string(idx) + ")";
                    return false;
                }
                transform_point(world, v, p + 3 * k);
                if (have_n) {
                    if (read_float(nrm->second, idx, 3, v))
                        transform_normal(world, v, n + 3 * k);
                    else
                        have_n = false;
                }
                if (have_uv && !read_float(tex->second, idx, 2, uv + 2 * k))
                    have_uv = false;
            }
            if (scene_add_triangle(out, p, have_n ? n : nullptr, have_uv ? uv : nullptr,
                                   material) < 0) {
                error = "out of memory";
                return false;
            }
        }
        return true;
    }

    bool node(int index, const mat4 &parent, int depth)
    {
        if (index < 0 || index >= (int)model.nodes.size() || depth > 64) {
            error = "node " + std::to_string(index) + " does not exist or nests too deep";
            return false;
        }
        const tinygltf::Node &n = model.nodes[index];
        mat4 world = mul(parent, node_local(n));
        if (n.mesh >= 0) {
            if (n.mesh >= (int)model.meshes.size()) {
                error = "node " + std::to_string(index) + " uses missing mesh";
                return false;
            }
            const tinygltf::Mesh &m = model.meshes[n.mesh];
            for (const tinygltf::Primitive &prim : m.primitives)
                if (!primitive(prim, world, m.name))
                    return false;
        }
        auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext != n.extensions.end() && ext->second.Has("light")) {
            int li = ext->second.Get("light").GetNumberAsInt();
            if (li >= 0 && li < (int)model.lights.size() && model.lights[li].type == "spot") {
                const tinygltf::Light &l = model.lights[li];
                scene_light sl{};
                const float zero[3] = {0, 0, 0};
                transform_point(world, zero, sl.position);
                double d[3] = {-world.m[8], -world.m[9], -world.m[10]}; // -Z axis
                double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                for (int a = 0; a < 3; a++) {
                    sl.direction[a] = len > 0 ? (float)(d[a] / len) : (a == 1 ? -1.0f : 0.0f);
                    sl.color[a] = l.color.size() == 3 ? (float)l.color[a] : 1.0f;
                }
                sl.intensity = (float)l.intensity;
                sl.outer_angle = (float)l.spot.outerConeAngle;
                sl.inner_angle = (float)l.spot.innerConeAngle;
                if (scene_add_light(out, &sl) < 0)
                    std::fprintf(stderr, "glTF: more than %d spot lights, light %d ignored\n",
                                 SCENE_MAX_LIGHTS, li);
            }
        }
        for (int child : n.children)
            if (!node(child, world, depth + 1))
                return false;
        return true;
    }

    bool materials()
    {
        material_base = (int)out->material_count;
        int texture_base = (int)out->texture_count;
        for (const tinygltf::Image &img : model.images) {
            int w = img.width, h = img.height, c = img.component;
            size_t need = (size_t)w * h * c * (img.bits == 16 ? 2 : 1);
            uint8_t *rgba = (uint8_t *)std::malloc((size_t)(w > 0 ? w : 1) * (h > 0 ? h : 1) * 4);
            if (!rgba)
                return error = "out of memory", false;
            if (w <= 0 || h <= 0 || c < 1 || c > 4 || img.image.size() < need) {
                // An image tinygltf could not decode: a white 1x1 keeps indices valid.
                w = h = 1;
                std::memset(rgba, 255, 4);
            } else {
                for (size_t i = 0; i < (size_t)w * h; i++)
                    for (int k = 0; k < 4; k++) {
                        size_t src = (i * c + (k < c ? k : 0)) * (img.bits == 16 ? 2 : 1);
                        uint8_t v = img.image[src + (img.bits == 16 ? 1 : 0)];
                        rgba[4 * i + k] = k < c ? v : (k == 3 ? 255 : img.image[i * c]);
                    }
            }
            if (scene_add_texture(out, w, h, rgba) < 0) {
                std::free(rgba);
                return error = "out of memory", false;
            }
        }
        for (const tinygltf::Material &m : model.materials) {
            scene_material sm{};
            const auto &pbr = m.pbrMetallicRoughness;
            for (int k = 0; k < 4; k++)
                sm.base_color[k] = pbr.baseColorFactor.size() == 4 ? (float)pbr.baseColorFactor[k] : 1.0f;
            sm.base_color_texture = -1;
            int ti = pbr.baseColorTexture.index;
            if (ti >= 0 && ti < (int)model.textures.size()) {
                int src = model.textures[ti].source;
                if (src >= 0 && src < (int)model.images.size())
                    sm.base_color_texture = texture_base + src;
            }
            double strength = 1.0;
            auto es = m.extensions.find("KHR_materials_emissive_strength");
            if (es != m.extensions.end() && es->second.Has("emissiveStrength"))
                strength = es->second.Get("emissiveStrength").GetNumberAsDouble();
            for (int k = 0; k < 3; k++)
                sm.emissive[k] = m.emissiveFactor.size() == 3 ? (float)(m.emissiveFactor[k] * strength) : 0.0f;
            sm.roughness = (float)pbr.roughnessFactor;
            if (scene_add_material(out, &sm) < 0)
                return error = "out of memory", false;
        }
        scene_material fallback = {{0.8f, 0.8f, 0.8f, 1.0f}, -1, {0, 0, 0}, 0.5f};
        default_material = scene_add_material(out, &fallback);
        return default_material >= 0 || (error = "out of memory", false);
    }
};

bool ends_with_glb(const char *path)
{
    size_t n = std::strlen(path);
    return n >= 4 && (strcasecmp(path + n - 4, ".glb") == 0);
}

} // namespace

extern "C" int gltf_import(const char *path, scene *out, char *err, size_t errlen)
{
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    bool ok;
    try {
        ok = ends_with_glb(path) ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                                 : loader.LoadASCIIFromFile(&model, &error, &warning, path);
    } catch (const std::exception &e) {
        ok = false;
        error = e.what();
    }
    if (!ok) {
        // tinygltf's messages span lines; keep the first for a one-line error.
        std::string first = error.substr(0, error.find('\n'));
        std::snprintf(err, errlen, "scene %s: cannot load glTF (%s)", path,
                      first.empty() ? "unreadable file" : first.c_str());
        return -1;
    }
    importer im{model, out, std::string(), 0, 0};
    try {
        if (!im.materials())
            throw std::runtime_error(im.error);
        int si = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (si < (int)model.scenes.size()) {
            for (int n : model.scenes[si].nodes)
                if (!im.node(n, identity(), 0))
                    throw std::runtime_error(im.error);
        } else { // no scenes: every node that is nobody's child is a root
            std::vector<bool> child(model.nodes.size(), false);
            for (const tinygltf::Node &n : model.nodes)
                for (int c : n.children)
                    if (c >= 0 && c < (int)child.size())
                        child[c] = true;
            for (int n = 0; n < (int)model.nodes.size(); n++)
                if (!child[n] && !im.node(n, identity(), 0))
                    throw std::runtime_error(im.error);
        }
    } catch (const std::exception &e) {
        std::snprintf(err, errlen, "scene %s: %s", path, e.what());
        return -1;
    }
    return 0;
}
