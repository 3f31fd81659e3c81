// gltf_import: glTF 2.0 (.gltf, .glb) into the C scene model, through tinygltf.
// The one C++ file of the project: everything C++ stays in here behind gltf_import().
// Reads meshes (TRIANGLES), node transforms, base colour factor and texture, emissive
// factor (times KHR_materials_emissive_strength), KHR_lights_punctual lights (spot, point,
// directional; `range` is a hint the spec lets renderers ignore, and we do) and cameras
// (perspective and orthographic) with their nodes' transforms.
//
// A scene file is untrusted input that every node loads: before anything is read, every
// index, offset, stride, count and type in the file is checked against what it refers to
// (validate()), and the first violation is refused with one line naming its JSON path.
// Images are decoded here, after that check, never by tinygltf; files are read only when
// they are regular files of bounded size.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

extern "C" {
#include "scene/scene.h"
}

namespace {

// Resource limits: a file may describe more than a node can hold; these turn that into a
// refusal instead of an allocation failure. 2^24 triangles is 1.6 GB of scene arrays.
constexpr size_t max_file_bytes = (size_t)1 << 30;
constexpr size_t max_triangles = (size_t)1 << 24;
constexpr int max_image_side = 16384;
constexpr long long max_image_pixels = 1LL << 26;
constexpr int max_node_depth = 64;

struct refusal : std::runtime_error {
    using std::runtime_error::runtime_error;
};

[[noreturn]] void refuse(const std::string &what)
{
    throw refusal(what);
}

std::string item(const std::string &array, size_t i)
{
    return array + "[" + std::to_string(i) + "]";
}

// Index v names one of n things called `what`; -1 only where the field is optional.
void check_index(long long v, size_t n, const std::string &field, const char *what, bool optional)
{
    if (optional && v == -1)
        return;
    if (v < 0 || (unsigned long long)v >= n)
        refuse(field + " " + std::to_string(v) + " out of range (" + std::to_string(n) + " " +
               what + ")");
}

// ---- files: regular files only, bounded in size (a uri may name /dev/zero or a FIFO) ----

bool fs_exists(const std::string &path, void *)
{
    struct stat st;
    return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string fs_expand(const std::string &path, void *)
{
    return path;
}

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *)
{
    int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) ||
        (unsigned long long)st.st_size > max_file_bytes) {
        if (err)
            *err += "File not found or not a regular file of at most 1 GiB: " + path + "\n";
        if (fd >= 0)
            close(fd);
        return false;
    }
    out->resize((size_t)st.st_size);
    size_t got = 0;
    while (got < out->size()) {
        ssize_t r = read(fd, out->data() + got, out->size() - got);
        if (r <= 0)
            break;
        got += (size_t)r;
    }
    close(fd);
    out->resize(got);
    return true;
}

bool fs_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err)
        *err += "writing is not supported\n";
    return false;
}

// tinygltf hands over an image's encoded bytes when they come from a uri; images in a
// bufferView are left for decode_images(), after their view has been checked.
bool keep_encoded(tinygltf::Image *image, const int, std::string *, std::string *, int, int,
                  const unsigned char *bytes, int size, void *)
{
    if (image->bufferView < 0 && bytes && size > 0)
        image->image.assign(bytes, bytes + size);
    return true;
}

// ---- validation: everything the importer will follow, checked once, before any read ----

const char *type_name(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
    }
}

const char *component_name(int c)
{
    switch (c) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "unknown";
    }
}

struct validator {
    const tinygltf::Model &model;

    void buffer_views()
    {
        for (size_t i = 0; i < model.bufferViews.size(); i++) {
            const tinygltf::BufferView &bv = model.bufferViews[i];
            std::string at = item("bufferViews", i);
            check_index(bv.buffer, model.buffers.size(), at + ".buffer", "buffers", false);
            size_t size = model.buffers[bv.buffer].data.size();
            if (bv.byteLength > size || bv.byteOffset > size - bv.byteLength)
                refuse(at + ": bytes " + std::to_string(bv.byteOffset) + " + " +
                       std::to_string(bv.byteLength) + " outside buffers[" +
                       std::to_string(bv.buffer) + "] (" + std::to_string(size) + " bytes)");
            if (bv.byteStride != 0 && (bv.byteStride < 4 || bv.byteStride > 252 || bv.byteStride % 4))
                refuse(at + ".byteStride " + std::to_string(bv.byteStride) +
                       " invalid (4 to 252, a multiple of 4)");
        }
    }

    void accessors()
    {
        for (size_t i = 0; i < model.accessors.size(); i++) {
            const tinygltf::Accessor &a = model.accessors[i];
            std::string at = item("accessors", i);
            if (a.sparse.isSparse)
                refuse(at + ".sparse: sparse accessors are not supported");
            int size = tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType);
            int comps = tinygltf::GetNumComponentsInType((uint32_t)a.type);
            if (size <= 0)
                refuse(at + ".componentType " + std::to_string(a.componentType) + " invalid");
            if (comps <= 0)
                refuse(at + ".type invalid");
            if (a.count < 1)
                refuse(at + ".count 0 invalid (at least 1)");
            if (a.bufferView < 0)
                refuse(at + ".bufferView missing (accessors without data are not supported)");
            check_index(a.bufferView, model.bufferViews.size(), at + ".bufferView", "bufferViews",
                        false);
            const tinygltf::BufferView &bv = model.bufferViews[a.bufferView];
            size_t elem = (size_t)size * (size_t)comps;
            size_t stride = bv.byteStride ? bv.byteStride : elem;
            if (stride < elem)
                refuse(at + ": element of " + std::to_string(elem) + " bytes wider than bufferViews[" +
                       std::to_string(a.bufferView) + "].byteStride " + std::to_string(stride));
            // byteOffset + (count - 1) * stride + elem <= byteLength, without overflow.
            if (a.byteOffset > bv.byteLength || elem > bv.byteLength - a.byteOffset ||
                a.count - 1 > (bv.byteLength - a.byteOffset - elem) / stride)
                refuse(at + ": byteOffset " + std::to_string(a.byteOffset) + " + count " +
                       std::to_string(a.count) + " x stride " + std::to_string(stride) +
                       " outside bufferViews[" + std::to_string(a.bufferView) + "] (" +
                       std::to_string(bv.byteLength) + " bytes)");
        }
    }

    // What the importer reads from an attribute: type and the component types it decodes.
    void attribute(int accessor, const std::string &at, int type, bool normalized_ok)
    {
        check_index(accessor, model.accessors.size(), at, "accessors", false);
        const tinygltf::Accessor &a = model.accessors[accessor];
        bool component_ok = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                            (normalized_ok && a.normalized &&
                             (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                              a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
        if (a.type != type || !component_ok)
            refuse(at + ": accessors[" + std::to_string(accessor) + "] is " + type_name(a.type) +
                   " " + component_name(a.componentType) + ", expected " + type_name(type) +
                   (normalized_ok ? " FLOAT or normalized UNSIGNED_BYTE/SHORT" : " FLOAT"));
    }

    void meshes()
    {
        for (size_t m = 0; m < model.meshes.size(); m++)
            for (size_t p = 0; p < model.meshes[m].primitives.size(); p++) {
                const tinygltf::Primitive &prim = model.meshes[m].primitives[p];
                std::string at = item(item("meshes", m) + ".primitives", p);
                for (const auto &kv : prim.attributes)
                    check_index(kv.second, model.accessors.size(), at + ".attributes." + kv.first,
                                "accessors", false);
                check_index(prim.material, model.materials.size(), at + ".material", "materials", true);
                if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
                    continue; // points and lines carry no surfaces: skipped
                auto pos = prim.attributes.find("POSITION");
                if (pos == prim.attributes.end())
                    refuse(at + ".attributes: no POSITION");
                attribute(pos->second, at + ".attributes.POSITION", TINYGLTF_TYPE_VEC3, false);
                size_t vertices = model.accessors[pos->second].count;
                for (const char *name : {"NORMAL", "TEXCOORD_0"}) {
                    auto it = prim.attributes.find(name);
                    if (it == prim.attributes.end())
                        continue;
                    bool uv = std::strcmp(name, "TEXCOORD_0") == 0;
                    std::string field = at + ".attributes." + name;
                    attribute(it->second, field, uv ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3, uv);
                    if (model.accessors[it->second].count != vertices)
                        refuse(field + ": count " + std::to_string(model.accessors[it->second].count) +
                               " differs from POSITION's " + std::to_string(vertices));
                }
                if (prim.indices < 0)
                    continue;
                check_index(prim.indices, model.accessors.size(), at + ".indices", "accessors", false);
                const tinygltf::Accessor &ia = model.accessors[prim.indices];
                if (ia.type != TINYGLTF_TYPE_SCALAR ||
                    (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                     ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                     ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
                    refuse(at + ".indices: accessors[" + std::to_string(prim.indices) + "] is " +
                           type_name(ia.type) + " " + component_name(ia.componentType) +
                           ", expected SCALAR UNSIGNED_BYTE/SHORT/INT");
            }
    }

    void materials()
    {
        for (size_t i = 0; i < model.images.size(); i++) {
            const tinygltf::Image &img = model.images[i];
            check_index(img.bufferView, model.bufferViews.size(), item("images", i) + ".bufferView",
                        "bufferViews", true);
        }
        for (size_t i = 0; i < model.textures.size(); i++)
            check_index(model.textures[i].source, model.images.size(),
                        item("textures", i) + ".source", "images", true);
        for (size_t i = 0; i < model.materials.size(); i++) {
            const tinygltf::Material &m = model.materials[i];
            std::string at = item("materials", i) + ".pbrMetallicRoughness.baseColorTexture";
            int ti = m.pbrMetallicRoughness.baseColorTexture.index;
            check_index(ti, model.textures.size(), at + ".index", "textures", true);
            if (ti >= 0 && model.textures[ti].source < 0)
                refuse(item("textures", (size_t)ti) + ".source missing (used by " +
                       item("materials", i) + ")");
        }
    }

    // Nodes form a forest: each has at most one parent, scenes name roots once each.
    void nodes()
    {
        std::vector<long long> parent(model.nodes.size(), -1);
        for (size_t i = 0; i < model.nodes.size(); i++) {
            const tinygltf::Node &n = model.nodes[i];
            std::string at = item("nodes", i);
            check_index(n.mesh, model.meshes.size(), at + ".mesh", "meshes", true);
            check_index(n.camera, model.cameras.size(), at + ".camera", "cameras", true);
            for (size_t c = 0; c < n.children.size(); c++) {
                std::string field = item(at + ".children", c);
                check_index(n.children[c], model.nodes.size(), field, "nodes", false);
                long long &p = parent[n.children[c]];
                if (p >= 0 || (size_t)n.children[c] == i)
                    refuse(field + ": nodes[" + std::to_string(n.children[c]) + "] already has a parent (" +
                           (p >= 0 ? item("nodes", (size_t)p) : at) + "); nodes must form trees");
                p = (long long)i;
            }
            auto ext = n.extensions.find("KHR_lights_punctual");
            if (ext != n.extensions.end() && ext->second.Has("light")) {
                const tinygltf::Value &l = ext->second.Get("light");
                if (!l.IsInt())
                    refuse(at + ".extensions.KHR_lights_punctual.light is not an integer");
                check_index(l.GetNumberAsInt(), model.lights.size(),
                            at + ".extensions.KHR_lights_punctual.light", "lights", false);
            }
        }
        for (size_t i = 0; i < model.nodes.size(); i++) { // a cycle has no root above it
            size_t steps = 0;
            for (long long p = parent[i]; p >= 0; p = parent[p])
                if (++steps > (size_t)max_node_depth)
                    refuse(item("nodes", i) + ": nested deeper than " + std::to_string(max_node_depth) +
                           " levels or in a cycle");
        }
        check_index(model.defaultScene, model.scenes.size(), "scene", "scenes", true);
        for (size_t s = 0; s < model.scenes.size(); s++) {
            std::vector<bool> seen(model.nodes.size(), false);
            for (size_t k = 0; k < model.scenes[s].nodes.size(); k++) {
                std::string field = item(item("scenes", s) + ".nodes", k);
                int n = model.scenes[s].nodes[k];
                check_index(n, model.nodes.size(), field, "nodes", false);
                if (parent[n] >= 0 || seen[n])
                    refuse(field + ": nodes[" + std::to_string(n) + "] is not a root or is listed twice");
                seen[n] = true;
            }
        }
    }

    // A number the importer uses: finite and within [lo, hi] (open ends where asked).
    static void check_number(double v, const std::string &field, double lo, double hi,
                             bool lo_open, bool hi_open, const char *range)
    {
        if (!std::isfinite(v) || v < lo || v > hi || (lo_open && v == lo) || (hi_open && v == hi))
            refuse(field + " " + std::to_string(v) + " invalid (" + range + ")");
    }

    void lights()
    {
        const double half_pi = 1.5707963267948966;
        for (size_t i = 0; i < model.lights.size(); i++) {
            const tinygltf::Light &l = model.lights[i];
            std::string at = item("extensions.KHR_lights_punctual.lights", i);
            if (l.type != "spot" && l.type != "point" && l.type != "directional")
                refuse(at + ".type \"" + l.type.substr(0, 40) +
                       "\" unknown (spot, point or directional)");
            check_number(l.intensity, at + ".intensity", 0, 1e12, false, false, "0 to 1e12");
            if (!l.color.empty() && l.color.size() != 3)
                refuse(at + ".color has " + std::to_string(l.color.size()) + " values, expected 3");
            for (size_t c = 0; c < l.color.size(); c++)
                check_number(l.color[c], item(at + ".color", c), 0, 1e12, false, false, "0 to 1e12");
            if (l.type != "spot")
                continue;
            check_number(l.spot.outerConeAngle, at + ".spot.outerConeAngle", 0, half_pi, true,
                         false, "0 < outer <= pi/2");
            check_number(l.spot.innerConeAngle, at + ".spot.innerConeAngle", 0,
                         l.spot.outerConeAngle, false, false, "0 <= inner <= outer");
        }
    }

    void cameras()
    {
        const double pi = 3.141592653589793;
        for (size_t i = 0; i < model.cameras.size(); i++) {
            const tinygltf::Camera &c = model.cameras[i];
            std::string at = item("cameras", i);
            if (c.type == "perspective") {
                const tinygltf::PerspectiveCamera &p = c.perspective;
                check_number(p.yfov, at + ".perspective.yfov", 0, pi, true, true, "0 < yfov < pi");
                check_number(p.znear, at + ".perspective.znear", 0, 1e30, true, false, "> 0");
                check_number(p.aspectRatio, at + ".perspective.aspectRatio", 0, 1e6, false, false,
                             "> 0");
                if (p.zfar != 0)
                    check_number(p.zfar, at + ".perspective.zfar", p.znear, 1e30, true, false,
                                 "> znear");
            } else if (c.type == "orthographic") {
                const tinygltf::OrthographicCamera &o = c.orthographic;
                check_number(o.xmag, at + ".orthographic.xmag", 0, 1e30, true, false, "> 0");
                check_number(o.ymag, at + ".orthographic.ymag", 0, 1e30, true, false, "> 0");
                check_number(o.znear, at + ".orthographic.znear", 0, 1e30, false, false, ">= 0");
                check_number(o.zfar, at + ".orthographic.zfar", o.znear, 1e30, true, false,
                             "> znear");
            } else {
                refuse(at + ".type \"" + c.type.substr(0, 40) +
                       "\" unknown (perspective or orthographic)");
            }
        }
    }

    void run()
    {
        buffer_views();
        accessors();
        meshes();
        materials();
        lights();
        cameras();
        nodes();
    }
};

// ---- import: reads only what validate() accepted ----

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
    std::vector<int> material_index; // glTF material -> scene material
    int default_material = -1;

    const unsigned char *element(int accessor, size_t i) const
    {
        const tinygltf::Accessor &a = model.accessors[accessor];
        const tinygltf::BufferView &bv = model.bufferViews[a.bufferView];
        size_t elem = (size_t)tinygltf::GetComponentSizeInBytes((uint32_t)a.componentType) *
                      (size_t)tinygltf::GetNumComponentsInType((uint32_t)a.type);
        size_t stride = bv.byteStride ? bv.byteStride : elem;
        return model.buffers[bv.buffer].data.data() + bv.byteOffset + a.byteOffset + i * stride;
    }

    // Float (or, for uvs, normalized unsigned) components of element i, as validated.
    void read_float(int accessor, size_t i, int comps, float *v) const
    {
        const unsigned char *p = element(accessor, i);
        switch (model.accessors[accessor].componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            for (int k = 0; k < comps; k++)
                v[k] = p[k] / 255.0f;
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            for (int k = 0; k < comps; k++) {
                uint16_t s;
                std::memcpy(&s, p + 2 * k, 2);
                v[k] = s / 65535.0f;
            }
            break;
        default:
            std::memcpy(v, p, (size_t)comps * sizeof(float));
        }
    }

    uint32_t read_index(int accessor, size_t i) const
    {
        const unsigned char *p = element(accessor, i);
        switch (model.accessors[accessor].componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t s;
            std::memcpy(&s, p, 2);
            return s;
        }
        default: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        }
    }

    void primitive(const tinygltf::Primitive &prim, const mat4 &world, const std::string &at)
    {
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
            return;
        int pos = prim.attributes.at("POSITION");
        auto nrm = prim.attributes.find("NORMAL");
        auto tex = prim.attributes.find("TEXCOORD_0");
        bool have_n = nrm != prim.attributes.end(), have_uv = tex != prim.attributes.end();
        size_t vertices = model.accessors[pos].count;
        size_t count = prim.indices >= 0 ? model.accessors[prim.indices].count : vertices;
        if (count / 3 > max_triangles - out->triangle_count)
            refuse(at + ": more than " + std::to_string(max_triangles) + " triangles in the scene");
        uint32_t material = prim.material >= 0 ? (uint32_t)material_index[prim.material]
                                               : (uint32_t)default_material;
        for (size_t t = 0; t + 2 < count; t += 3) {
            float p[9], n[9], uv[6];
            for (int k = 0; k < 3; k++) {
                size_t idx = t + k;
                if (prim.indices >= 0) {
                    idx = read_index(prim.indices, t + k);
                    if (idx >= vertices)
                        refuse(at + ".indices: accessors[" + std::to_string(prim.indices) + "][" +
                               std::to_string(t + k) + "] = " + std::to_string(idx) +
                               " out of range (" + std::to_string(vertices) + " vertices)");
                }
                float v[3];
                read_float(pos, idx, 3, v);
                transform_point(world, v, p + 3 * k);
                if (have_n) {
                    read_float(nrm->second, idx, 3, v);
                    transform_normal(world, v, n + 3 * k);
                }
                if (have_uv)
                    read_float(tex->second, idx, 2, uv + 2 * k);
            }
            if (scene_add_triangle(out, p, have_n ? n : nullptr, have_uv ? uv : nullptr,
                                   material) < 0)
                refuse("out of memory");
        }
    }

    // The node's -Z axis in the world, unit; false when its transform flattens it.
    static bool axis(const mat4 &world, int column, double sign, float out[3])
    {
        double d[3] = {sign * world.m[4 * column], sign * world.m[4 * column + 1],
                       sign * world.m[4 * column + 2]};
        double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(len > 0) || !std::isfinite(len))
            return false;
        for (int a = 0; a < 3; a++)
            out[a] = (float)(d[a] / len);
        return true;
    }

    void light(int li, const mat4 &world)
    {
        const tinygltf::Light &l = model.lights[li];
        scene_light sl{};
        const float zero[3] = {0, 0, 0};
        transform_point(world, zero, sl.position);
        if (!axis(world, 2, -1.0, sl.direction)) // spot axis and travel: the node's -Z
            sl.direction[1] = -1.0f;
        for (int a = 0; a < 3; a++)
            sl.color[a] = l.color.size() == 3 ? (float)l.color[a] : 1.0f;
        sl.intensity = (float)l.intensity;
        if (l.type == "spot") {
            sl.type = SCENE_LIGHT_SPOT;
            sl.outer_angle = (float)l.spot.outerConeAngle;
            sl.inner_angle = (float)l.spot.innerConeAngle;
        } else {
            sl.type = l.type == "point" ? SCENE_LIGHT_POINT : SCENE_LIGHT_DIRECTIONAL;
        }
        if (scene_add_light(out, &sl) < 0)
            std::fprintf(stderr, "glTF: more than %d lights, light %d ignored\n", SCENE_MAX_LIGHTS,
                         li);
    }

    static void name_copy(char *dst, size_t n, const std::string &src)
    {
        std::snprintf(dst, n, "%s", src.c_str());
    }

    void camera(const tinygltf::Node &n, const mat4 &world, const std::string &at)
    {
        const tinygltf::Camera &c = model.cameras[n.camera];
        scene_camera sc{};
        const float zero[3] = {0, 0, 0};
        transform_point(world, zero, sc.position);
        float forward[3];
        if (!axis(world, 2, -1.0, forward) || !axis(world, 1, 1.0, sc.up) ||
            std::fabs(forward[0] * sc.up[0] + forward[1] * sc.up[1] + forward[2] * sc.up[2]) > 0.999f)
            refuse(at + ": the camera's transform has no view direction or up (zero scale?)");
        for (int a = 0; a < 3; a++)
            sc.target[a] = sc.position[a] + forward[a];
        sc.valid = 1;
        if (c.type == "orthographic") {
            sc.orthographic = 1;
            sc.ymag = (float)c.orthographic.ymag;
            sc.aspect = (float)(c.orthographic.xmag / c.orthographic.ymag);
            sc.znear = (float)c.orthographic.znear;
            sc.zfar = (float)c.orthographic.zfar;
        } else {
            sc.yfov = (float)c.perspective.yfov;
            sc.aspect = (float)c.perspective.aspectRatio;
            sc.znear = (float)c.perspective.znear;
            sc.zfar = (float)c.perspective.zfar;
        }
        name_copy(sc.name, sizeof sc.name, n.name.empty() ? c.name : n.name);
        name_copy(sc.camera_name, sizeof sc.camera_name, c.name);
        if (scene_add_camera(out, &sc) < 0)
            refuse("out of memory");
    }

    void node(int index, const mat4 &parent)
    {
        const tinygltf::Node &n = model.nodes[index];
        mat4 world = mul(parent, node_local(n));
        if (n.mesh >= 0) {
            const tinygltf::Mesh &m = model.meshes[n.mesh];
            for (size_t p = 0; p < m.primitives.size(); p++)
                primitive(m.primitives[p], world, item(item("meshes", n.mesh) + ".primitives", p));
        }
        auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext != n.extensions.end() && ext->second.Has("light"))
            light(ext->second.Get("light").GetNumberAsInt(), world);
        if (n.camera >= 0)
            camera(n, world, item("nodes", (size_t)index));
        for (int child : n.children)
            node(child, world);
    }

    // Decodes one image to RGBA8 (sRGB-encoded, as glTF stores base colour).
    int texture(int image)
    {
        const tinygltf::Image &img = model.images[image];
        std::string at = item("images", (size_t)image);
        const unsigned char *bytes;
        size_t size;
        if (img.bufferView >= 0) {
            const tinygltf::BufferView &bv = model.bufferViews[img.bufferView];
            bytes = model.buffers[bv.buffer].data.data() + bv.byteOffset;
            size = bv.byteLength;
        } else {
            bytes = img.image.data();
            size = img.image.size();
        }
        if (size == 0)
            refuse(at + (img.uri.empty() ? ": no data"
                                         : ".uri \"" + img.uri.substr(0, 80) + "\": file not found or empty"));
        int w, h, c;
        if (size > INT32_MAX || !stbi_info_from_memory(bytes, (int)size, &w, &h, &c))
            refuse(at + ": cannot decode (" + (stbi_failure_reason() ? stbi_failure_reason() : "unknown format") + ")");
        if (w > max_image_side || h > max_image_side || (long long)w * h > max_image_pixels)
            refuse(at + ": " + std::to_string(w) + "x" + std::to_string(h) + " is larger than " +
                   std::to_string(max_image_side) + " a side or 2^26 pixels");
        uint8_t *rgba = stbi_load_from_memory(bytes, (int)size, &w, &h, &c, 4);
        if (!rgba)
            refuse(at + ": cannot decode (" + (stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")");
        // The scene owns malloc'ed pixels; stb_image's allocator is malloc.
        int t = scene_add_texture(out, w, h, rgba);
        if (t < 0) {
            stbi_image_free(rgba);
            refuse("out of memory");
        }
        return t;
    }

    void materials()
    {
        std::vector<int> texture_of(model.images.size(), -1);
        for (const tinygltf::Material &m : model.materials) {
            scene_material sm{};
            const auto &pbr = m.pbrMetallicRoughness;
            for (int k = 0; k < 4; k++)
                sm.base_color[k] = pbr.baseColorFactor.size() == 4 ? (float)pbr.baseColorFactor[k] : 1.0f;
            sm.base_color_texture = -1;
            if (pbr.baseColorTexture.index >= 0) {
                int src = model.textures[pbr.baseColorTexture.index].source;
                if (texture_of[src] < 0)
                    texture_of[src] = texture(src);
                sm.base_color_texture = texture_of[src];
            }
            double strength = 1.0;
            auto es = m.extensions.find("KHR_materials_emissive_strength");
            if (es != m.extensions.end() && es->second.Has("emissiveStrength"))
                strength = es->second.Get("emissiveStrength").GetNumberAsDouble();
            for (int k = 0; k < 3; k++)
                sm.emissive[k] = m.emissiveFactor.size() == 3 ? (float)(m.emissiveFactor[k] * strength) : 0.0f;
            sm.roughness = (float)pbr.roughnessFactor;
            int index = scene_add_material(out, &sm);
            if (index < 0)
                refuse("out of memory");
            material_index.push_back(index);
        }
        scene_material fallback = {{0.8f, 0.8f, 0.8f, 1.0f}, -1, {0, 0, 0}, 0.5f};
        default_material = scene_add_material(out, &fallback);
        if (default_material < 0)
            refuse("out of memory");
    }

    void run()
    {
        materials();
        roots();
        if (out->camera_count > 0) // the file's first camera is the view
            out->camera = out->cameras[0];
    }

    void roots()
    {
        if (model.scenes.empty()) { // no scenes: every node that is nobody's child is a root
            std::vector<bool> child(model.nodes.size(), false);
            for (const tinygltf::Node &n : model.nodes)
                for (int c : n.children)
                    child[c] = true;
            for (size_t n = 0; n < model.nodes.size(); n++)
                if (!child[n])
                    node((int)n, identity());
            return;
        }
        for (int n : model.scenes[model.defaultScene >= 0 ? model.defaultScene : 0].nodes)
            node(n, identity());
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
    loader.SetFsCallbacks({fs_exists, fs_expand, fs_read, fs_write, nullptr});
    loader.SetImageLoader(keep_encoded, nullptr);
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
    try {
        validator{model}.run();
        importer{model, out, {}, -1}.run();
    } catch (const std::exception &e) {
        std::snprintf(err, errlen, "scene %s: %s", path, e.what());
        return -1;
    }
    return 0;
}
