// Assimp's scene -> the neutral record: meshes, the node hierarchy, cameras
// and lights (docs/importing.md). Materials are in asset_assimp_materials.cpp.
#include <assimp/scene.h>

#include <cmath>
#include <limits>
#include <utility>

#include "scene/asset_internal.h"

namespace pt {
namespace {

constexpr double kPiD = 3.14159265358979323846;

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
Vec3f to_vec(const aiVector3D& v) { return Vec3f(v.x, v.y, v.z); }

Affine to_affine(const aiMatrix4x4& m) {
  Affine a;
  const float* rows[3] = {&m.a1, &m.b1, &m.c1};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) a.m[i][j] = rows[i][j];
  }
  return a;
}

Vec3f apply_point(const Affine& a, Vec3f p) {
  return Vec3f(static_cast<float>(a.m[0][0] * p.x + a.m[0][1] * p.y + a.m[0][2] * p.z + a.m[0][3]),
               static_cast<float>(a.m[1][0] * p.x + a.m[1][1] * p.y + a.m[1][2] * p.z + a.m[1][3]),
               static_cast<float>(a.m[2][0] * p.x + a.m[2][1] * p.y + a.m[2][2] * p.z + a.m[2][3]));
}
Vec3f apply_vector(const Affine& a, Vec3f v) { return apply_point(a, v) - apply_point(a, Vec3f(0.0f)); }

// The transform of the node named `name` to the file's world space (the
// identity if no node has the name).
Affine node_to_world(const aiScene& scene, const aiString& name) {
  Affine world;
  for (const aiNode* n = scene.mRootNode ? scene.mRootNode->FindNode(name) : nullptr; n; n = n->mParent)
    world = to_affine(n->mTransformation) * world;
  return world;
}

// One mesh's vertices and triangles; false with `error` for data we cannot use.
bool convert_mesh(const aiMesh& m, int uv_set, AssetMesh& out, std::string& error) {
  if (m.mNumVertices >= std::numeric_limits<uint32_t>::max() || m.mNumFaces > std::numeric_limits<uint32_t>::max() / 3) {
    error = "mesh '" + std::string(m.mName.C_Str()) + "' has more vertices or triangles than a mesh can index";
    return false;
  }
  TriangleMesh& t = out.mesh;
  const bool normals = m.HasNormals(), uvs = uv_set >= 0 && m.HasTextureCoords(static_cast<unsigned>(uv_set));
  const bool tangents = m.HasTangentsAndBitangents() && normals;
  // Exact sizes (no doubling growth left unused under the build's peak); one
  // spare position: the Embree backend can share the buffer.
  t.positions.reserve(m.mNumVertices + 1);
  if (normals) t.normals.reserve(m.mNumVertices);
  if (uvs) t.uvs.reserve(m.mNumVertices);
  if (tangents) out.tangents.reserve(m.mNumVertices);
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    if (!finite(m.mVertices[v])) {
      error = "mesh '" + std::string(m.mName.C_Str()) + "': vertex " + std::to_string(v) + " has a non-finite position";
      return false;
    }
    t.positions.push_back(to_vec(m.mVertices[v]));
    if (normals) t.normals.push_back(finite(m.mNormals[v]) ? to_vec(m.mNormals[v]) : Vec3f(0.0f));  // zero: ng
    if (uvs) {
      const aiVector3D& c = m.mTextureCoords[uv_set][v];
      t.uvs.push_back(std::isfinite(c.x) && std::isfinite(c.y) ? Vec2f(c.x, c.y) : Vec2f());
    }
    if (tangents) {
      const Vec3f n = to_vec(m.mNormals[v]), tv = to_vec(m.mTangents[v]), b = to_vec(m.mBitangents[v]);
      out.tangents.emplace_back(tv, dot(cross(n, tv), b) < 0.0f ? -1.0f : 1.0f);
    }
  }
  t.indices.reserve(3 * static_cast<std::size_t>(m.mNumFaces));
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices != 3) continue;  // triangulated: only stray points and lines remain
    for (int k = 0; k < 3; ++k) t.indices.push_back(face.mIndices[k]);
  }
  return true;
}

}  // namespace

bool convert_meshes(const aiScene& scene, const std::vector<int>& uv_set, ImportedAsset& out, Diagnostics& diag,
                    const SourceLocation& where) {
  out.meshes.resize(scene.mNumMeshes);
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    AssetMesh& mesh = out.meshes[i];
    mesh.name = m.mName.C_Str();
    mesh.material = static_cast<int>(m.mMaterialIndex);
    if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
      out.counts.skipped_n("point and line primitives", m.mNumFaces);
      continue;  // left empty; placements skip it
    }
    const int set = m.mMaterialIndex < uv_set.size() ? uv_set[m.mMaterialIndex] : 0;
    std::string error;
    if (!convert_mesh(m, set, mesh, error)) {
      diag.error(where, "cannot read '" + out.path + "': " + error);
      return false;
    }
    if (m.mNumBones > 0) out.counts.skipped_n("skins (meshes kept in their bind pose)", 1);
    if (m.mNumAnimMeshes > 0) out.counts.skipped_n("morph targets", m.mNumAnimMeshes);
    // Read, but nothing renders them yet: a scene mesh has no tangents until normal maps exist.
    if (!mesh.tangents.empty()) out.counts.skipped_n("mesh tangents (normal maps take tangents from the texture coordinates)", 1);
  }
  if (scene.mNumAnimations > 0) out.counts.skipped_n("animations", scene.mNumAnimations);
  return true;
}

void convert_placements(const aiScene& scene, ImportedAsset& out) {
  if (!scene.mRootNode) return;
  // Depth first with an explicit stack: a file's hierarchy may be deep.
  std::vector<std::pair<const aiNode*, Affine>> stack{{scene.mRootNode, to_affine(scene.mRootNode->mTransformation)}};
  while (!stack.empty()) {
    auto [node, world] = stack.back();
    stack.pop_back();
    if (node->mNumMeshes > 0) {
      AssetPlacement p;
      p.node = node->mName.C_Str();
      p.to_world = world;
      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        const unsigned m = node->mMeshes[k];
        if (m < out.meshes.size() && !out.meshes[m].mesh.indices.empty()) p.meshes.push_back(static_cast<int>(m));
      }
      if (!p.meshes.empty()) out.placements.push_back(std::move(p));
    }
    for (unsigned c = node->mNumChildren; c-- > 0;)
      stack.emplace_back(node->mChildren[c], world * to_affine(node->mChildren[c]->mTransformation));
  }
}

void convert_cameras(const aiScene& scene, ImportedAsset& out) {
  for (unsigned i = 0; i < scene.mNumCameras; ++i) {
    const aiCamera& c = *scene.mCameras[i];
    const Affine w = node_to_world(scene, c.mName);
    AssetCamera cam;
    cam.name = c.mName.C_Str();
    // glTF defines the camera at its node's origin looking down -z, y up.
    // Assimp 5.2's glTF reader also copies the node's translation into
    // mPosition (counting it twice), so its position is not read for glTF.
    const bool gltf = out.format == AssetFormat::Gltf || out.format == AssetFormat::Glb;
    const Vec3f eye = gltf ? Vec3f(0.0f) : to_vec(c.mPosition);
    const Vec3f forward = gltf ? Vec3f(0, 0, -1) : to_vec(c.mLookAt), up = gltf ? Vec3f(0, 1, 0) : to_vec(c.mUp);
    cam.position = apply_point(w, eye);
    cam.look_at = apply_point(w, eye + forward);
    cam.up = apply_vector(w, up);
    cam.aspect = c.mAspect > 0.0f && std::isfinite(c.mAspect) ? c.mAspect : 0.0f;
    cam.orthographic = c.mOrthographicWidth > 0.0f;
    if (cam.orthographic) {
      // Half the visible width; the height follows from the aspect ratio.
      cam.view_height = 2.0f * c.mOrthographicWidth / (cam.aspect > 0.0f ? cam.aspect : 1.0f);
    } else {
      // Assimp's horizontal angle: glTF's yfov times the aspect ratio (5.2's
      // reader), or the full horizontal angle (COLLADA).
      const double h = c.mHorizontalFOV;
      double y = h;
      if (cam.aspect > 0.0f) y = gltf ? h / cam.aspect : 2.0 * std::atan(std::tan(h / 2.0) / cam.aspect);
      cam.fov_y_deg = static_cast<float>(y * 180.0 / kPiD);
    }
    out.cameras.push_back(cam);
  }
}

void convert_lights(const aiScene& scene, ImportedAsset& out) {
  const bool gltf = out.format == AssetFormat::Gltf || out.format == AssetFormat::Glb;
  for (unsigned i = 0; i < scene.mNumLights; ++i) {
    const aiLight& l = *scene.mLights[i];
    AssetLight light;
    light.name = l.mName.C_Str();
    switch (l.mType) {
      case aiLightSource_POINT: light.type = AssetLight::Type::Point; break;
      case aiLightSource_SPOT: light.type = AssetLight::Type::Spot; break;
      case aiLightSource_DIRECTIONAL: light.type = AssetLight::Type::Directional; break;
      default: out.counts.skipped_n("lights of other kinds (ambient, area)", 1); continue;
    }
    const Affine w = node_to_world(scene, l.mName);
    light.position = apply_point(w, to_vec(l.mPosition));
    light.direction = apply_vector(w, to_vec(l.mDirection));
    const RGB colour(l.mColorDiffuse.r, l.mColorDiffuse.g, l.mColorDiffuse.b);  // glTF: colour x intensity
    if (light.type == AssetLight::Type::Directional) {
      light.intensity = colour;  // glTF lux, COLLADA colour: irradiance
    } else if (gltf) {
      light.intensity = colour / static_cast<float>(kPiD);  // candela: I = cd / pi (docs/importing.md)
    } else if (l.mAttenuationQuadratic > 0.0f) {
      light.intensity = colour / l.mAttenuationQuadratic;  // COLLADA: 1 / (c + l d + q d^2)
    } else {
      light.inverse_square = false;  // constant attenuation: no falloff
      light.intensity = colour / (l.mAttenuationConstant > 0.0f ? l.mAttenuationConstant : 1.0f);
    }
    if (light.type == AssetLight::Type::Spot) {
      const float outer = l.mAngleOuterCone, inner = std::min(l.mAngleInnerCone, outer);
      light.cone_angle_deg = static_cast<float>(outer * 180.0 / kPiD);
      light.cone_delta_deg = static_cast<float>((outer - inner) * 180.0 / kPiD);
    }
    out.lights.push_back(light);
  }
}

}  // namespace pt
