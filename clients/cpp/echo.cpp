// The smallest client of refrast's pipe protocol (docs/protocol.md): it answers every draw at once,
// with one fragment per triangle at pixel (0, 0), and rasterizes nothing. It measures what the
// pipe itself costs (conformance/benches/pipe.rs); it is no rasterizer, and certifying it fails.
//   g++ -O2 -std=c++17 -o echo echo.cpp

#include <cstdint>
#include <cstdio>
#include <vector>

int main() {
    std::printf("refrast-protocol 1\nname cpp-echo\nready\n");
    std::fflush(stdout);
    char line[4096];
    std::vector<char> data;
    std::vector<uint32_t> record(11, 0);
    while (std::fgets(line, sizeof line, stdin)) {
        unsigned vertices = 0, triangles = 0;
        if (std::sscanf(line, "%*s width=%*u height=%*u vertices=%u triangles=%u", &vertices, &triangles) != 2) {
            std::fprintf(stderr, "echo: cannot read `%s`\n", line);
            return 1;
        }
        data.resize(16 * size_t(vertices) + 12 * size_t(triangles));
        if (std::fread(data.data(), 1, data.size(), stdin) != data.size()) return 0;
        std::printf("fragments %u\n", triangles);
        for (uint32_t t = 0; t < triangles; ++t) {
            record[2] = t;
            std::fwrite(record.data(), 4, record.size(), stdout);
        }
        std::printf("end\n");
        std::fflush(stdout);
    }
    return 0;
}
