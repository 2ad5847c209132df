// MeshShape's serialization as Bullet's btTriangleMeshShapeData, and the loader that reads such
// shapes back into MeshShapes.
//
// Bullet's format (btDefaultSerializer): a 12-byte header ("BULLETf"/"BULLETd", '-' for 8-byte
// pointers, 'v' little endian, version), then chunks: a btChunk (code, length, the writer's
// unique id for the data, DNA struct index, element count) followed by `length` bytes of
// structs as laid out in the writer's memory. Pointers inside the structs hold the unique id
// of the chunk they point to. The last chunk is the DNA that lets Bullet's importer convert
// other layouts; the loader here reads only the native layout, so it needs no DNA.
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btStridingMeshInterface.h>
#include <LinearMath/btSerializer.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>

#include "adb/bullet/mesh_serialization.h"
#include "adb/bullet/mesh_shape.h"

namespace adb {
namespace {

// Bullet's chunk lengths are ints: an array chunk holds at most INT_MAX bytes.
constexpr std::size_t kMaxChunkBytes = static_cast<std::size_t>(INT_MAX);

// Allocates a chunk of `count` elements of T; the caller fills it and finalizes it.
template <class T>
btChunk* allocateArray(btSerializer* serializer, std::size_t count) {
  return serializer->allocate(sizeof(T), static_cast<int>(count));
}

}  // namespace

int MeshShape::calculateSerializeBufferSize() const {
  return static_cast<int>(sizeof(btTriangleMeshShapeData));
}

const char* MeshShape::serialize(void* dataBuffer, btSerializer* serializer) const {
  // The unscaled shared mesh: the scaling is stored beside it, as btBvhTriangleMeshShape
  // stores its meshInterface's, so a reader rebuilds the same scaled shape.
  const TriangleMesh& mesh = m_data->mesh;
  const std::size_t nv = mesh.vertices().size(), nt = mesh.triangleCount();
  if (nv > kMaxChunkBytes / sizeof(btVector3DoubleData) ||
      nt > kMaxChunkBytes / (3 * sizeof(btIntIndexData))) {
    throw MeshError("MeshShape::serialize: mesh '" + mesh.name() + "' has " +
                    std::to_string(nv) + " vertices and " + std::to_string(nt) +
                    " triangles; Bullet's format holds at most " +
                    std::to_string(kMaxChunkBytes / sizeof(btVector3DoubleData)) +
                    " vertices and " +
                    std::to_string(kMaxChunkBytes / (3 * sizeof(btIntIndexData))) +
                    " triangles per shape");
  }

  auto* out = static_cast<btTriangleMeshShapeData*>(dataBuffer);
  // Name and padding as every Bullet shape writes them; the type as Bullet's own mesh shape,
  // which is what its importer knows how to build.
  btCollisionShape::serialize(&out->m_collisionShapeData, serializer);
  out->m_collisionShapeData.m_shapeType = TRIANGLE_MESH_SHAPE_PROXYTYPE;

  btStridingMeshInterfaceData& meshInterface = out->m_meshInterface;
  btChunk* partChunk = allocateArray<btMeshPartData>(serializer, 1);
  auto* part = static_cast<btMeshPartData*>(partChunk->m_oldPtr);
  std::memset(part, 0, sizeof(*part));
  part->m_numTriangles = static_cast<int>(nt);
  part->m_numVertices = static_cast<int>(nv);

  // Vertices as doubles in either precision: the round trip is then exact.
  btChunk* vertexChunk = allocateArray<btVector3DoubleData>(serializer, nv);
  auto* vertices = static_cast<btVector3DoubleData*>(vertexChunk->m_oldPtr);
  for (std::size_t i = 0; i < nv; ++i) {
    const Vec3& v = mesh.vertices()[i];
    vertices[i].m_floats[0] = v.x();
    vertices[i].m_floats[1] = v.y();
    vertices[i].m_floats[2] = v.z();
    vertices[i].m_floats[3] = 0.0;
  }
  part->m_vertices3d =
      static_cast<btVector3DoubleData*>(serializer->getUniquePointer(vertexChunk->m_oldPtr));
  serializer->finalizeChunk(vertexChunk, "btVector3DoubleData", BT_ARRAY_CODE,
                            vertexChunk->m_oldPtr);

  btChunk* indexChunk = allocateArray<btIntIndexData>(serializer, 3 * nt);
  auto* indices = static_cast<btIntIndexData*>(indexChunk->m_oldPtr);
  for (std::size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      indices[3 * t + k].m_value = static_cast<int>(mesh.triangles()[t][k]);
    }
  }
  part->m_indices32 =
      static_cast<btIntIndexData*>(serializer->getUniquePointer(indexChunk->m_oldPtr));
  serializer->finalizeChunk(indexChunk, "btIntIndexData", BT_ARRAY_CODE, indexChunk->m_oldPtr);

  meshInterface.m_meshPartsPtr =
      static_cast<btMeshPartData*>(serializer->getUniquePointer(partChunk->m_oldPtr));
  serializer->finalizeChunk(partChunk, "btMeshPartData", BT_ARRAY_CODE, partChunk->m_oldPtr);
  meshInterface.m_numMeshParts = 1;
  m_scaling.serializeFloat(meshInterface.m_scaling);
  std::memset(meshInterface.m_padding, 0, sizeof(meshInterface.m_padding));

  // No Bullet BVH: the importer builds its own, and adb rebuilds its tree.
  out->m_quantizedFloatBvh = nullptr;
  out->m_quantizedDoubleBvh = nullptr;
  out->m_triangleInfoMap = nullptr;
  out->m_collisionMargin = static_cast<float>(getMargin());
  std::memset(out->m_pad3, 0, sizeof(out->m_pad3));
  return "btTriangleMeshShapeData";
}

namespace {

// A native-layout .bullet buffer: its chunks by the unique id that pointers hold. Every read
// is bounds-checked and copied out with memcpy (chunks follow one another unaligned).
class ChunkReader {
 public:
  ChunkReader(const void* buffer, std::size_t size)
      : m_bytes(static_cast<const unsigned char*>(buffer)) {
    constexpr std::size_t kHeader = 12;
    if (!buffer || size < kHeader || std::memcmp(m_bytes, "BULLET", 6) != 0 ||
        (m_bytes[6] != 'f' && m_bytes[6] != 'd')) {
      fail("not a Bullet serialization buffer (no \"BULLETf\"/\"BULLETd\" header)");
    }
    const char pointerSize = sizeof(void*) == 8 ? '-' : '_';
    const std::uint16_t one = 1;
    unsigned char firstByte = 0;
    std::memcpy(&firstByte, &one, 1);
    const char byteOrder = firstByte == 1 ? 'v' : 'V';
    if (m_bytes[7] != pointerSize || m_bytes[8] != byteOrder) {
      fail("written with another pointer size or byte order than this machine's; read it "
           "with Bullet's btBulletWorldImporter");
    }
    std::size_t at = kHeader;
    while (at < size) {
      if (size - at < sizeof(btChunk)) {
        fail("truncated chunk header at byte " + std::to_string(at));
      }
      btChunk c;
      std::memcpy(&c, m_bytes + at, sizeof(c));
      at += sizeof(btChunk);
      if (c.m_length < 0 || static_cast<std::size_t>(c.m_length) > size - at) {
        fail("chunk at byte " + std::to_string(at - sizeof(btChunk)) + " claims " +
             std::to_string(c.m_length) + " bytes, past the end of the buffer");
      }
      m_chunks.push_back(Chunk{c.m_chunkCode, at, static_cast<std::size_t>(c.m_length)});
      m_byId.emplace(reinterpret_cast<std::uintptr_t>(c.m_oldPtr), m_chunks.size() - 1);
      at += static_cast<std::size_t>(c.m_length);
    }
  }

  struct Chunk {
    int code;
    std::size_t offset, length;
  };
  const std::vector<Chunk>& chunks() const { return m_chunks; }

  template <class T>
  T read(const Chunk& c) const {
    if (c.length < sizeof(T)) fail("a chunk is shorter than the struct it holds");
    T value;
    std::memcpy(static_cast<void*>(&value), m_bytes + c.offset, sizeof(T));
    return value;
  }

  /// The `count` Ts that `pointer` (a unique id) points to.
  template <class T>
  std::vector<T> readArray(const void* pointer, std::size_t count, const char* what) const {
    const auto it = m_byId.find(reinterpret_cast<std::uintptr_t>(pointer));
    if (it == m_byId.end()) fail(std::string(what) + " points to no chunk");
    const Chunk& c = m_chunks[it->second];
    if (count > c.length / sizeof(T)) {
      fail(std::string(what) + ": " + std::to_string(count) + " elements expected, the chunk "
           "holds " + std::to_string(c.length / sizeof(T)));
    }
    std::vector<T> out(count);
    if (count > 0) {
      std::memcpy(static_cast<void*>(out.data()), m_bytes + c.offset, count * sizeof(T));
    }
    return out;
  }

  /// The NUL-terminated string `pointer` points to, or "" for none.
  std::string readName(const void* pointer) const {
    if (!pointer) return {};
    const auto it = m_byId.find(reinterpret_cast<std::uintptr_t>(pointer));
    if (it == m_byId.end()) fail("a shape name points to no chunk");
    const Chunk& c = m_chunks[it->second];
    const char* s = reinterpret_cast<const char*>(m_bytes + c.offset);
    const void* end = std::memchr(s, 0, c.length);
    return std::string(s, end ? static_cast<const char*>(end) - s : c.length);
  }

  [[noreturn]] static void fail(const std::string& why) {
    throw MeshError("loadMeshShapes: " + why);
  }

 private:
  const unsigned char* m_bytes;
  std::vector<Chunk> m_chunks;
  std::unordered_map<std::uintptr_t, std::size_t> m_byId;
};

std::size_t checkedCount(int n, const char* what) {
  if (n < 0) ChunkReader::fail(std::string(what) + " is negative (" + std::to_string(n) + ")");
  return static_cast<std::size_t>(n);
}

// Appends one mesh part's vertices and triangles (indices shifted past earlier parts').
void readPart(const ChunkReader& reader, const btMeshPartData& part, std::vector<Vec3>& vertices,
              std::vector<Triangle>& triangles) {
  const std::size_t nv = checkedCount(part.m_numVertices, "a part's vertex count");
  const std::size_t nt = checkedCount(part.m_numTriangles, "a part's triangle count");
  const std::size_t base = vertices.size();
  if (part.m_vertices3d) {
    for (const btVector3DoubleData& v :
         reader.readArray<btVector3DoubleData>(part.m_vertices3d, nv, "a part's vertices")) {
      vertices.emplace_back(v.m_floats[0], v.m_floats[1], v.m_floats[2]);
    }
  } else if (part.m_vertices3f) {
    for (const btVector3FloatData& v :
         reader.readArray<btVector3FloatData>(part.m_vertices3f, nv, "a part's vertices")) {
      vertices.emplace_back(v.m_floats[0], v.m_floats[1], v.m_floats[2]);
    }
  } else if (nv > 0) {
    ChunkReader::fail("a mesh part has vertices but no vertex array");
  }
  // Indices as unsigned: a negative one becomes huge and fails the range check below.
  std::vector<std::uint32_t> index;
  if (part.m_indices32) {
    for (const btIntIndexData& i :
         reader.readArray<btIntIndexData>(part.m_indices32, 3 * nt, "a part's indices")) {
      index.push_back(static_cast<std::uint32_t>(i.m_value));
    }
  } else if (part.m_3indices16) {
    for (const btShortIntIndexTripletData& t : reader.readArray<btShortIntIndexTripletData>(
             part.m_3indices16, nt, "a part's indices")) {
      for (short v : t.m_values) index.push_back(static_cast<std::uint16_t>(v));
    }
  } else if (part.m_3indices8) {
    for (const btCharIndexTripletData& t : reader.readArray<btCharIndexTripletData>(
             part.m_3indices8, nt, "a part's indices")) {
      for (unsigned char v : t.m_values) index.push_back(v);
    }
  } else if (part.m_indices16) {
    for (const btShortIntIndexData& i :
         reader.readArray<btShortIntIndexData>(part.m_indices16, 3 * nt, "a part's indices")) {
      index.push_back(static_cast<std::uint16_t>(i.m_value));
    }
  } else if (nt > 0) {
    ChunkReader::fail("a mesh part has triangles but no index array");
  }
  if (base + nv > UINT32_MAX) ChunkReader::fail("more than 2^32 vertices in one mesh");
  for (std::size_t t = 0; t < nt; ++t) {
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = index[3 * t + k];
      if (i >= nv) {
        ChunkReader::fail("triangle " + std::to_string(t) + " of a part references vertex " +
                          std::to_string(i) + ", but the part has " + std::to_string(nv));
      }
      tri[k] = static_cast<std::uint32_t>(base + i);
    }
    triangles.push_back(tri);
  }
}

}  // namespace

std::vector<LoadedMeshShape> loadMeshShapes(const void* buffer, std::size_t size,
                                            const BuildSettings& settings) {
  const ChunkReader reader(buffer, size);
  std::vector<LoadedMeshShape> out;
  // Equal meshes share one MeshData (a world usually had one per model, not per body).
  std::multimap<std::pair<std::size_t, std::size_t>, std::shared_ptr<const MeshData>> built;
  for (const ChunkReader::Chunk& c : reader.chunks()) {
    if (c.code != BT_SHAPE_CODE || c.length < sizeof(btCollisionShapeData)) continue;
    if (reader.read<btCollisionShapeData>(c).m_shapeType != TRIANGLE_MESH_SHAPE_PROXYTYPE) {
      continue;
    }
    const auto data = reader.read<btTriangleMeshShapeData>(c);
    const btStridingMeshInterfaceData& meshInterface = data.m_meshInterface;
    const std::size_t parts = checkedCount(meshInterface.m_numMeshParts, "a mesh's part count");
    std::vector<Vec3> vertices;
    std::vector<Triangle> triangles;
    for (const btMeshPartData& part :
         reader.readArray<btMeshPartData>(meshInterface.m_meshPartsPtr, parts, "a mesh's parts")) {
      readPart(reader, part, vertices, triangles);
    }
    LoadedMeshShape loaded;
    loaded.name = reader.readName(data.m_collisionShapeData.m_name);

    std::shared_ptr<const MeshData> mesh;
    const auto key = std::make_pair(vertices.size(), triangles.size());
    for (auto [it, end] = built.equal_range(key); it != end && !mesh; ++it) {
      if (it->second->mesh.vertices() == vertices && it->second->mesh.triangles() == triangles) {
        mesh = it->second;
      }
    }
    if (!mesh) {
      mesh = MeshData::build(TriangleMesh(std::move(vertices), std::move(triangles),
                                          loaded.name.empty() ? "serialized mesh" : loaded.name),
                             settings);
      built.emplace(key, mesh);
    }
    const float margin = data.m_collisionMargin;
    const float* s = meshInterface.m_scaling.m_floats;
    if (!(std::isfinite(margin) && margin >= 0.0f) ||
        !(std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2]) && s[0] > 0.0f &&
          s[1] > 0.0f && s[2] > 0.0f)) {
      ChunkReader::fail("shape '" + mesh->mesh.name() + "' has a negative or non-finite margin "
                        "or a non-positive or non-finite scaling");
    }
    loaded.shape = std::make_unique<MeshShape>(std::move(mesh));
    loaded.shape->setMargin(static_cast<btScalar>(margin));
    btVector3 scaling;
    scaling.deSerializeFloat(meshInterface.m_scaling);
    loaded.shape->setLocalScaling(scaling);
    out.push_back(std::move(loaded));
  }
  return out;
}

}  // namespace adb
