// mvr-import FILE: reads a model in one of assimp's formats (FBX, Collada,
// 3DS) and writes it to standard output as mvr/assets/imported_model.h lays
// it out. mvr runs it as a child process under memory and time limits
// (mvr/assets/assimp_import.h): assimp's readers are not safe on every input,
// and a crash here is one line there. Exit 1 with one line on stderr when
// the file cannot be read.
#include <cmath>
#include <sys/resource.h>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdio>
#include <iostream>
#include <string>

#include "mvr/assets/imported_model.h"

namespace {

using namespace mvr;

glm::vec3 colorOf(const aiMaterial& m, const char* key, unsigned type, unsigned index, glm::vec3 fallback) {
  aiColor3D c;
  return m.Get(key, type, index, c) == AI_SUCCESS ? glm::vec3(c.r, c.g, c.b) : fallback;
}

// assimp's material as ours: the diffuse (or PBR base) colour and its
// texture, the specular colour times its strength and the shininess
// (only for the shading models that have a highlight: not for Collada's
// lambert, which assimp calls Gouraud), or its metallic-roughness where it
// has one; "*K" names an embedded image.
Material materialOf(const aiMaterial& m) {
  Material out;
  aiString name;
  if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = name.C_Str();
  out.diffuse = colorOf(m, AI_MATKEY_COLOR_DIFFUSE, colorOf(m, AI_MATKEY_BASE_COLOR, out.diffuse));
  float strength = 1.0f, shininess = 0.0f;
  m.Get(AI_MATKEY_SHININESS_STRENGTH, strength);
  m.Get(AI_MATKEY_SHININESS, shininess);
  int model = aiShadingMode_Phong;
  m.Get(AI_MATKEY_SHADING_MODEL, model);
  const bool highlight = shininess > 0.0f && (model == aiShadingMode_Phong || model == aiShadingMode_Blinn ||
                                               model == aiShadingMode_CookTorrance || model == aiShadingMode_Fresnel ||
                                               model == aiShadingMode_PBR_BRDF);
  out.specular = highlight ? colorOf(m, AI_MATKEY_COLOR_SPECULAR, glm::vec3(0.0f)) * strength : glm::vec3(0.0f);
  out.shininess = shininess;
  // A metallic-roughness material (FBX's and others' PBR, as assimp
  // reports it): glTF's model, base colour first.
  float metallic = 0.0f, roughness = 1.0f;
  const bool hasMetallic = m.Get(AI_MATKEY_METALLIC_FACTOR, metallic) == AI_SUCCESS;
  const bool hasRoughness = m.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness) == AI_SUCCESS;
  if (hasMetallic || hasRoughness)
    out.setMetallicRoughness(colorOf(m, AI_MATKEY_BASE_COLOR, out.diffuse), std::isfinite(metallic) ? metallic : 0.0f,
                             std::isfinite(roughness) ? roughness : 1.0f);
  out.emission = glm::clamp(colorOf(m, AI_MATKEY_COLOR_EMISSIVE, glm::vec3(0.0f)), 0.0f, 1.0f);
  // Two-sided always: assimp's readers report "one-sided" by default for
  // formats whose files do not say, and a missing back face is worse than
  // one drawn.
  out.twoSided = true;
  aiString texture;
  if (m.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS ||
      m.GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == AI_SUCCESS)
    out.texture = texture.C_Str();
  return out;
}

EmbeddedImage embeddedOf(const aiTexture& t) {
  EmbeddedImage e;
  e.hint = t.achFormatHint;
  const auto* bytes = reinterpret_cast<const uint8_t*>(t.pcData);
  if (t.mHeight == 0) {  // compressed: mWidth bytes
    e.bytes.assign(bytes, bytes + t.mWidth);
  } else {
    e.width = int(t.mWidth), e.height = int(t.mHeight);
    e.bytes.assign(bytes, bytes + size_t(t.mWidth) * t.mHeight * 4);  // aiTexel: b, g, r, a
  }
  return e;
}

// The meshes, already in world coordinates (aiProcess_PreTransformVertices).
void addMeshes(const aiScene& in, Scene& s) {
  bool anyUv = false;
  for (unsigned i = 0; i < in.mNumMeshes; ++i) anyUv = anyUv || in.mMeshes[i]->HasTextureCoords(0);
  for (unsigned i = 0; i < in.mNumMeshes; ++i) {
    const aiMesh& m = *in.mMeshes[i];
    const auto base = uint32_t(s.positions.size());
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D& p = m.mVertices[v];
      s.positions.emplace_back(p.x, p.y, p.z);
      const aiVector3D n = m.HasNormals() ? m.mNormals[v] : aiVector3D(0, 0, 1);
      s.normals.emplace_back(n.x, n.y, n.z);
      s.colors.push_back(m.HasVertexColors(0)
                             ? glm::clamp(glm::vec3(m.mColors[0][v].r, m.mColors[0][v].g, m.mColors[0][v].b), 0.0f, 1.0f)
                             : glm::vec3(1.0f));
      if (anyUv) s.uvs.push_back(m.HasTextureCoords(0) ? glm::vec2(m.mTextureCoords[0][v].x, m.mTextureCoords[0][v].y)
                                                       : glm::vec2(0.0f));
    }
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3) {
        ++s.droppedFaces;
        continue;
      }
      s.triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]);
      s.materialIds.push_back(m.mMaterialIndex);
    }
  }
}

}  // namespace

// Limits of its own, set first: an input that makes assimp allocate
// without end or loop stops here, and mvr reports it. (Not under
// AddressSanitizer, which reserves terabytes of address space.)
void limitSelf() {
  const rlimit cpu{120, 120};
  setrlimit(RLIMIT_CPU, &cpu);
#if !defined(__SANITIZE_ADDRESS__)
  const rlimit memory{rlim_t(8) << 30, rlim_t(8) << 30};
  setrlimit(RLIMIT_AS, &memory);
#endif
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mvr-import FILE (mvr runs it; it writes the model to standard output)\n");
    return 2;
  }
  limitSelf();
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* in = importer.ReadFile(
      argv[1], aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                   aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!in || !in->mRootNode) {
    std::string why = importer.GetErrorString();
    if (const size_t nl = why.find('\n'); nl != std::string::npos) why.resize(nl);
    std::fprintf(stderr, "%s\n", why.empty() ? "cannot read the model" : why.c_str());
    return 1;
  }
  ImportedModel model;
  for (unsigned i = 0; i < in->mNumMaterials; ++i) model.scene.materials.push_back(materialOf(*in->mMaterials[i]));
  if (model.scene.materials.empty()) model.scene.materials.emplace_back();
  for (unsigned i = 0; i < in->mNumTextures; ++i) model.embedded.push_back(embeddedOf(*in->mTextures[i]));
  for (Material& m : model.scene.materials)  // FBX names an embedded image by its file name
    if (const aiTexture* t = m.texture.empty() || m.texture[0] == '*' ? nullptr : in->GetEmbeddedTexture(m.texture.c_str()))
      for (unsigned i = 0; i < in->mNumTextures; ++i)
        if (in->mTextures[i] == t) m.texture = "*" + std::to_string(i);
  addMeshes(*in, model.scene);
  if (in->mNumAnimations) model.scene.warnings.push_back("animations not played: the scene as it stands");
  if (in->mNumCameras || in->mNumLights) model.scene.warnings.push_back("its cameras and lights not read: framed and lit as a mesh");
  std::ios::sync_with_stdio(false);
  writeImportedModel(std::cout, model);
  std::cout.flush();
  return std::cout ? 0 : 1;
}
