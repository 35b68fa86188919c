// Seed 000's software rasterizer (Graphics Programming I, "Software Rasterization Part I"), as
// its five lab steps describe it, certified by refrast over a pipe (docs/protocol.md). One file, no
// dependencies:  g++ -O2 -std=c++17 -o lab000 lab000.cpp
//                refrast certify --exec ./lab000
//
// - Projection: divide x and y by the view-space depth (clip w), keep that depth as z, then
//   x = (x + 1)/2 * W, y = (1 - y)/2 * H. No clipping: a vertex behind the eye divides by a
//   negative depth and lands mirrored.
// - Inside test: the 2D cross product of each edge with the vector from its start to the pixel,
//   in float, on unsnapped coordinates; the pixel is the point (px, py), its top-left corner
//   (the lab never adds 1/2). The lab's triangle is clockwise, so a pixel is inside when all
//   three are >= 0: counter-clockwise triangles draw nothing, and every edge owns its samples.
// - Bounding box: the vertices' smallest and largest x and y, clamped to the screen.
// - Barycentrics: each cross product over the total cross product, in screen space.
// - Depth: the weights interpolate the view depth; fragments carry 1/2 + 1/2 z/(1 + |z|), a
//   strictly increasing map of it into [0, 1].
//
// refrast's zoo holds the same lab in Rust (`lab000`); this port gives the same verdicts.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

// ---- the pipe protocol, version 1 (docs/protocol.md) ---------------------------------------

struct Draw {
    uint32_t width = 0, height = 0, vertices = 0, triangles = 0;
    char cull[16] = {}, front_face[8] = {}, compare[16] = {}, write[8] = {}, range[32] = {}, far[8] = {};
    float clear = 1.0f;
    std::vector<float> positions;      // 4 per vertex: x, y, z, w
    std::vector<uint32_t> indices;     // 3 per triangle
};

// One fragment record: x, y, primitive, front-facing, depth, 3 + 3 barycentrics (44 bytes).
struct Record {
    uint32_t x, y, primitive, front_facing;
    float depth, barycentric[3], screen[3];
};
static_assert(sizeof(Record) == 44, "records are 11 little-endian 4-byte words");

bool read_request(Draw& d, char* op) {
    char line[4096];
    if (!std::fgets(line, sizeof line, stdin)) return false;
    // refrast always sends the keys in this order.
    int n = std::sscanf(line,
        "%15s width=%u height=%u vertices=%u triangles=%u cull=%15s front-face=%7s depth-compare=%15s "
        "depth-write=%7s depth-clear=%f depth-range=%31s far-clipping=%7s",
        op, &d.width, &d.height, &d.vertices, &d.triangles, d.cull, d.front_face, d.compare, d.write,
        &d.clear, d.range, d.far);
    if (n != 12) {
        std::fprintf(stderr, "lab000: cannot read the request `%s`\n", line);
        return false;
    }
    d.positions.resize(4 * size_t(d.vertices));
    d.indices.resize(3 * size_t(d.triangles));
    return std::fread(d.positions.data(), 16, d.vertices, stdin) == d.vertices &&
           std::fread(d.indices.data(), 12, d.triangles, stdin) == d.triangles;
}

void reply_fragments(const std::vector<Record>& out) {
    std::printf("fragments %zu\n", out.size());
    std::fwrite(out.data(), sizeof(Record), out.size(), stdout);
    std::printf("end\n");
    std::fflush(stdout);
}

// ---- the lab's rasterizer ------------------------------------------------------------------

struct Vec2 { float x, y; };

float cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }

float window_depth(float view_z) {
    double z = view_z;
    return float(0.5 + 0.5 * z / (1.0 + std::fabs(z)));
}

// The projection stage; false for a vertex with any coordinate that is not a finite number.
bool project(const float* p, float width, float height, Vec2& screen, float& depth) {
    float nx = p[0] / p[3], ny = p[1] / p[3];
    screen = {(nx + 1.0f) / 2.0f * width, (1.0f - ny) / 2.0f * height};
    depth = p[3];
    for (int k = 0; k < 4; ++k)
        if (!std::isfinite(p[k])) return false;
    return std::isfinite(screen.x) && std::isfinite(screen.y);
}

std::vector<Record> rasterize(const Draw& d) {
    std::vector<Record> out;
    float wf = float(d.width), hf = float(d.height);
    // Every drawn triangle is clockwise on screen, the only winding the sign test accepts.
    uint32_t front = std::strcmp(d.front_face, "cw") == 0 ? 1 : 0;
    for (uint32_t t = 0; t < d.triangles; ++t) {
        Vec2 v[3];
        float z[3];
        bool ok = true;
        for (int k = 0; k < 3; ++k)
            ok = project(&d.positions[4 * size_t(d.indices[3 * t + k])], wf, hf, v[k], z[k]) && ok;
        if (!ok) continue;
        float total = cross(sub(v[1], v[0]), sub(v[2], v[0]));
        // Zero area gives 0/0 weights; negative area (counter-clockwise) has no inside.
        if (!(total > 0.0f && std::isfinite(total))) continue;
        auto clamp = [](float value, uint32_t max) {
            return uint32_t(std::fmin(std::fmax(value, 0.0f), float(max - 1)));
        };
        uint32_t x0 = clamp(std::fmin(std::fmin(v[0].x, v[1].x), v[2].x), d.width);
        uint32_t x1 = clamp(std::fmax(std::fmax(v[0].x, v[1].x), v[2].x), d.width);
        uint32_t y0 = clamp(std::fmin(std::fmin(v[0].y, v[1].y), v[2].y), d.height);
        uint32_t y1 = clamp(std::fmax(std::fmax(v[0].y, v[1].y), v[2].y), d.height);
        for (uint32_t py = y0; py <= y1; ++py) {
            for (uint32_t px = x0; px <= x1; ++px) {
                Vec2 p = {float(px), float(py)};
                float c0 = cross(sub(v[2], v[1]), sub(p, v[1]));
                float c1 = cross(sub(v[0], v[2]), sub(p, v[2]));
                float c2 = cross(sub(v[1], v[0]), sub(p, v[0]));
                if (!(c0 >= 0.0f && c1 >= 0.0f && c2 >= 0.0f)) continue;
                float w[3] = {c0 / total, c1 / total, c2 / total};
                float depth = w[0] * z[0] + w[1] * z[1] + w[2] * z[2];
                if (!(std::isfinite(depth) && std::isfinite(w[0]) && std::isfinite(w[1]) && std::isfinite(w[2])))
                    continue;
                out.push_back({px, py, t, front, window_depth(depth), {w[0], w[1], w[2]}, {w[0], w[1], w[2]}});
            }
        }
    }
    return out;
}

}  // namespace

int main() {
    // Version 1 on purpose: refrast still speaks it, and this client shows that it does (version 2
    // adds a request's topology and samples and a fragment's sample word, docs/protocol.md).
    std::printf(
        "refrast-protocol 1\n"
        "name cpp-lab000\n"
        "about clients/cpp/lab000.cpp, seed 000's rasterizer in C++\n"
        "snapping float\n"
        "fill none\n"
        "depth other\n"
        "tolerance 1\n"
        "precision 18\n"
        "features screen-barycentrics guard-band\n"
        "cull none\n"
        "front-face ccw cw\n"
        "far-clipping off\n"
        "depth-range zero-to-one\n"
        "ready\n");
    std::fflush(stdout);
    Draw d;
    char op[16];
    while (read_request(d, op)) {
        if (std::strcmp(op, "rasterize") != 0) {
            std::printf("unsupported no %s here\n", op);
            std::fflush(stdout);
            continue;
        }
        uint32_t bad = 0;
        bool in_range = true;
        for (uint32_t i : d.indices)
            if (i >= d.vertices) { in_range = false; bad = i; break; }
        if (!in_range) {
            std::printf("error vertex %u does not exist: the draw has %u\n", bad, d.vertices);
            std::fflush(stdout);
            continue;
        }
        reply_fragments(rasterize(d));
    }
    return 0;
}
