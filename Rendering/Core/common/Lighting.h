// VTK's volume light model, shared by the CPU engines (the slice mapper's shader mirrors it):
// every light's ambient, diffuse and specular colour times its intensity, directional,
// positional and spot lights with attenuation, Blinn-Phong highlights, two-sided lighting as
// the renderer says.
#ifndef accelvolume_Lighting_h
#define accelvolume_Lighting_h

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace accelvolume
{

struct SceneLight
{
  bool positional = false;
  float axis[3] = { 0, 0, -1 };     // eye space, unit: the way the light shines (focal - position)
  float position[3] = { 0, 0, 0 };  // eye space (positional lights)
  float ambient[3] = { 0, 0, 0 };   // colours times intensity
  float diffuse[3] = { 1, 1, 1 };
  float specular[3] = { 1, 1, 1 };
  float attenuation[3] = { 1, 0, 0 }; // constant, linear, quadratic (positional lights)
  float cosCone = -2.0f;              // spot lights (cone angle <= 90 degrees): cos(angle)
  float exponent = 1.0f;              // spot falloff
};

struct LightModel
{
  float ambient = 0.1f, diffuse = 0.7f, specular = 0.2f, specularPower = 10.0f;
  bool twoSided = true;
  // VTK's single default headlight: the ambient term is ambient * colour (no light colour).
  bool headlightOnly = false;
  bool anyPositional = false;
  std::vector<SceneLight> lights;
};

/**
 * Shading terms at an eye-space point for a unit outward normal (minus the normalised
 * gradient) and the unit vector towards the viewer: the final colour is
 * colour * factor + highlight (per channel). `power(x)` is x^specularPower for x in [0, 1].
 */
template <typename Power>
void LightingTerms(const LightModel& model, const float normal[3], const float point[3],
  const float toViewer[3], Power power, float factor[3], float highlight[3])
{
  float ambient[3] = { 0, 0, 0 };
  float diffuse[3] = { 0, 0, 0 };
  float specular[3] = { 0, 0, 0 };
  for (const SceneLight& light : model.lights)
  {
    float toLight[3] = { -light.axis[0], -light.axis[1], -light.axis[2] };
    float attenuation = 1.0f;
    if (light.positional)
    {
      float d[3] = { light.position[0] - point[0], light.position[1] - point[1],
        light.position[2] - point[2] };
      const float distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (distance > 0)
      {
        for (int c = 0; c < 3; ++c)
        {
          toLight[c] = d[c] / distance;
        }
      }
      const float* a = light.attenuation;
      const float denominator = a[0] + a[1] * distance + a[2] * distance * distance;
      attenuation = denominator > 0 ? 1.0f / denominator : 1.0f;
      if (light.cosCone >= -1.0f)
      {
        const float spot =
          -(toLight[0] * light.axis[0] + toLight[1] * light.axis[1] + toLight[2] * light.axis[2]);
        attenuation = spot >= light.cosCone ? attenuation * std::pow(std::max(spot, 0.0f),
                                                              light.exponent)
                                            : 0.0f;
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      ambient[c] += light.ambient[c];
    }
    float nDotL = normal[0] * toLight[0] + normal[1] * toLight[1] + normal[2] * toLight[2];
    nDotL = model.twoSided ? std::abs(nDotL) : nDotL;
    if (nDotL > 0 && attenuation > 0)
    {
      for (int c = 0; c < 3; ++c)
      {
        diffuse[c] += attenuation * nDotL * light.diffuse[c];
      }
    }
    float half[3] = { toLight[0] + toViewer[0], toLight[1] + toViewer[1], toLight[2] + toViewer[2] };
    const float halfLength = std::sqrt(half[0] * half[0] + half[1] * half[1] + half[2] * half[2]);
    if (halfLength > 0 && attenuation > 0)
    {
      float nDotH = (normal[0] * half[0] + normal[1] * half[1] + normal[2] * half[2]) / halfLength;
      nDotH = model.twoSided ? std::abs(nDotH) : nDotH;
      if (nDotH > 0)
      {
        const float term = attenuation * power(std::min(nDotH, 1.0f));
        for (int c = 0; c < 3; ++c)
        {
          specular[c] += term * light.specular[c];
        }
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    factor[c] =
      model.ambient * (model.headlightOnly ? 1.0f : ambient[c]) + model.diffuse * diffuse[c];
    highlight[c] = model.specular * specular[c];
  }
}

/**
 * LightingTerms with each light's unit direction towards it and unit half vector fixed (a
 * directional light, or a light at the eye seen along a ray through the eye); the same terms
 * up to float rounding, without a square root per light.
 */
template <typename Power>
inline void FixedLightingTerms(const LightModel& model, const float normal[3], const float (*toLight)[3],
  const float (*half)[3], Power power, float factor[3], float highlight[3])
{
  float ambient[3] = { 0, 0, 0 };
  float diffuse[3] = { 0, 0, 0 };
  float specular[3] = { 0, 0, 0 };
  std::size_t index = 0;
  for (const SceneLight& light : model.lights)
  {
    const float* l = toLight[index];
    const float* h = half[index++];
    float nDotL = normal[0] * l[0] + normal[1] * l[1] + normal[2] * l[2];
    float nDotH = normal[0] * h[0] + normal[1] * h[1] + normal[2] * h[2];
    if (model.twoSided)
    {
      nDotL = std::abs(nDotL);
      nDotH = std::abs(nDotH);
    }
    // Selects rather than branches (the caller may run this for every sample of a ray).
    const float d = std::max(nDotL, 0.0f);
    const float highlightTerm = power(std::min(std::max(nDotH, 0.0f), 1.0f));
    const float term = nDotH > 0 ? highlightTerm : 0.0f;
    for (int c = 0; c < 3; ++c)
    {
      ambient[c] += light.ambient[c];
      diffuse[c] += d * light.diffuse[c];
      specular[c] += term * light.specular[c];
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    factor[c] =
      model.ambient * (model.headlightOnly ? 1.0f : ambient[c]) + model.diffuse * diffuse[c];
    highlight[c] = model.specular * specular[c];
  }
}

/** The terms for a vanishing gradient: ambient only. */
inline void AmbientTerms(const LightModel& model, float factor[3], float highlight[3])
{
  for (int c = 0; c < 3; ++c)
  {
    float ambient = 0;
    for (const SceneLight& light : model.lights)
    {
      ambient += light.ambient[c];
    }
    factor[c] = model.ambient * (model.headlightOnly ? 1.0f : ambient);
    highlight[c] = 0;
  }
}

}

#endif
