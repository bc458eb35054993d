#include "mvr/tone_map.h"

#include <algorithm>
#include <cmath>

namespace mvr {
namespace {

glm::vec3 aces(glm::vec3 c) {
  // sRGB to XYZ to D60 to AP1 with the RRT's saturation, and back; columns.
  const glm::mat3 in(glm::vec3(0.59719f, 0.07600f, 0.02840f), glm::vec3(0.35458f, 0.90834f, 0.13383f),
                     glm::vec3(0.04823f, 0.01566f, 0.83777f));
  const glm::mat3 out(glm::vec3(1.60475f, -0.10208f, -0.00327f), glm::vec3(-0.53108f, 1.10813f, -0.07276f),
                      glm::vec3(-0.07367f, -0.00605f, 1.07602f));
  c = in * (c / 0.6f);
  c = (c * (c + 0.0245786f) - 0.000090537f) / (c * (0.983729f * c + 0.4329510f) + 0.238081f);
  return glm::clamp(out * c, 0.0f, 1.0f);
}

glm::vec3 agxContrast(const glm::vec3& x) {
  const glm::vec3 x2 = x * x, x4 = x2 * x2;
  return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 + 0.1191f * x - 0.00232f;
}

glm::vec3 agx(glm::vec3 c) {
  const glm::mat3 toRec2020(glm::vec3(0.6274f, 0.0691f, 0.0164f), glm::vec3(0.3293f, 0.9195f, 0.0880f),
                            glm::vec3(0.0433f, 0.0113f, 0.8956f));
  const glm::mat3 toSrgb(glm::vec3(1.6605f, -0.1246f, -0.0182f), glm::vec3(-0.5876f, 1.1329f, -0.1006f),
                         glm::vec3(-0.0728f, -0.0083f, 1.1187f));
  const glm::mat3 inset(glm::vec3(0.856627153315983f, 0.137318972929847f, 0.11189821299995f),
                        glm::vec3(0.0951212405381588f, 0.761241990602591f, 0.0767994186031903f),
                        glm::vec3(0.0482516061458583f, 0.101439036467562f, 0.811302368396859f));
  const glm::mat3 outset(glm::vec3(1.1271005818144368f, -0.1413297634984383f, -0.14132976349843826f),
                         glm::vec3(-0.11060664309660323f, 1.157823702216272f, -0.11060664309660294f),
                         glm::vec3(-0.016493938717834573f, -0.016493938717834257f, 1.2519364065950405f));
  constexpr float kMinEv = -12.47393f, kMaxEv = 4.026069f;  // log2(2^-10 0.18), log2(2^6.5 0.18)
  c = inset * (toRec2020 * c);
  c = glm::clamp((glm::log2(glm::max(c, 1e-10f)) - kMinEv) / (kMaxEv - kMinEv), 0.0f, 1.0f);
  c = outset * agxContrast(c);
  c = glm::pow(glm::max(c, 0.0f), glm::vec3(2.2f));
  return glm::clamp(toSrgb * c, 0.0f, 1.0f);
}

glm::vec3 neutral(glm::vec3 c) {
  constexpr float kStart = 0.8f - 0.04f, kDesaturation = 0.15f;
  const float x = std::min({c.r, c.g, c.b});
  c -= x < 0.08f ? x - 6.25f * x * x : 0.04f;
  const float peak = std::max({c.r, c.g, c.b});
  if (peak < kStart) return c;
  const float d = 1.0f - kStart, newPeak = 1.0f - d * d / (peak + d - kStart);
  c *= newPeak / peak;
  const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
  return glm::mix(c, glm::vec3(newPeak), g);
}

}  // namespace

std::optional<ToneMap> toneMapNamed(const std::string& name) {
  for (ToneMap m : kToneMaps)
    if (name == toneMapName(m)) return m;
  return std::nullopt;
}

const char* toneMapName(ToneMap map) {
  switch (map) {
    case ToneMap::None: return "none";
    case ToneMap::Aces: return "aces";
    case ToneMap::Agx: return "agx";
    case ToneMap::Neutral: return "neutral";
  }
  return "none";
}

glm::vec3 toneMap(ToneMap map, const glm::vec3& linear) {
  switch (map) {
    case ToneMap::None: return linear;
    case ToneMap::Aces: return aces(linear);
    case ToneMap::Agx: return agx(linear);
    case ToneMap::Neutral: return neutral(linear);
  }
  return linear;
}

}  // namespace mvr
