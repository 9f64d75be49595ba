// Shear-warp's per-frame shading: VTK's light model for a quantized normal (PhongTerms) and
// Lacroute's shading table over every normal code (BuildShadingTable).
#include "shearwarp/ShearWarpCompositor.h"

#include <algorithm>
#include <cmath>

namespace accelvolume
{

void PhongTerms(const CompositeTables& t, const float g[3], float factor[3], float specular[3])
{
  AmbientTerms(t.lighting, factor, specular);
  float n[3];
  for (int r = 0; r < 3; ++r)
  {
    n[r] = t.normalMatrix[r][0] * g[0] + t.normalMatrix[r][1] * g[1] + t.normalMatrix[r][2] * g[2];
  }
  const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(length > 0))
  {
    return; // a vanishing gradient: ambient only, as the ray caster
  }
  for (float& value : n)
  {
    value /= -length;
  }
  const float toViewer[3] = { 0, 0, 1 };
  const float power = t.lighting.specularPower;
  LightingTerms(
    t.lighting, n, t.lightingPoint, toViewer, [power](float x) { return std::pow(x, power); },
    factor, specular);
}

namespace
{
// Row `code` of the shading table (the last, NormalCodes, is NoNormal: ambient only).
void ShadingRow(CompositeTables& t, int code, bool white)
{
  float factor[3];
  float specular[3];
  AmbientTerms(t.lighting, factor, specular);
  if (code < NormalCodes)
  {
    float g[3];
    DecodeNormal(static_cast<std::uint16_t>(code), g);
    PhongTerms(t, g, factor, specular);
  }
  float* row = &t.shading[static_cast<std::size_t>(t.shadingStride) * code];
  if (white)
  {
    row[0] = factor[0];
    row[1] = specular[0];
  }
  else
  {
    std::copy(factor, factor + 3, row);
    std::copy(specular, specular + 3, row + 3);
  }
}
}

void BuildShadingTable(CompositeTables& t, const ParallelFor& parallel)
{
  // One row per quantized normal: the view vector is +z in eye space for every pixel of a
  // parallel view, so the specular term is fixed per normal too. White lights (VTK's default)
  // need one factor and one highlight per normal, not three.
  bool white = true;
  for (const SceneLight& light : t.lighting.lights)
  {
    for (const float* colour : { light.ambient, light.diffuse, light.specular })
    {
      white = white && colour[0] == colour[1] && colour[0] == colour[2];
    }
  }
  t.shadingStride = white ? 2 : 6;
  t.shading.assign(static_cast<std::size_t>(t.shadingStride) * (NormalCodes + 1), 0.0f);
  parallel(NormalCodes + 1,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t code = begin; code < end; ++code)
      {
        ShadingRow(t, static_cast<int>(code), white);
      }
    });
}

}
