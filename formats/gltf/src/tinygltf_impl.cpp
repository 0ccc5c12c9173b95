// tinygltf's implementation, compiled here rather than linked from Debian's libtinygltf, which is built
// without Draco. Its options (Draco on; no image decoding; no file system) are set for the whole target in
// formats/gltf/CMakeLists.txt, so every file of it sees the same tinygltf types.
#define TINYGLTF_IMPLEMENTATION
#include <fstream> // tinygltf 2.7 uses std::ofstream in its (unused) file writers even with TINYGLTF_NO_FS
#include <tiny_gltf.h>
