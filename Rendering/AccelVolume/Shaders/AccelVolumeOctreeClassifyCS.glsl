// Min-max octree classification on the GPU, into the slice mapper's skipping textures, without a
// read-back of the levels. A prelude gives #version and ACCELVOLUME_CLASSIFY_BLOCKS:
// 0: one invocation per leaf (x, y, z): its (min, max) from the level-0 buffer (Morton order,
//    raw values), normalised to the transfer table's range, is transparent when every table
//    entry a sample of that range can read has opacity 0 (prefix counts of the non-zero
//    entries); 1 (transparent) or 0 into the leaf image, and the transparent leaves counted.
// 1: one invocation per block of `blockLeaves`^3 leaves: transparent where all its leaves are.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform ivec3 leafGrid;   // leaves per axis
uniform ivec3 blockGrid;  // blocks per axis
uniform int blockLeaves;  // leaves per block edge

#if ACCELVOLUME_CLASSIFY_BLOCKS
layout(r8, binding = 0) uniform readonly image3D leaves;
layout(r8, binding = 1) uniform writeonly image3D blocks;

void main()
{
  ivec3 block = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(block, blockGrid)))
  {
    return;
  }
  ivec3 first = block * blockLeaves;
  ivec3 last = min(first + ivec3(blockLeaves), leafGrid) - ivec3(1);
  float transparent = 1.0;
  for (int z = first.z; z <= last.z; ++z)
  {
    for (int y = first.y; y <= last.y; ++y)
    {
      for (int x = first.x; x <= last.x; ++x)
      {
        transparent = min(transparent, imageLoad(leaves, ivec3(x, y, z)).r);
      }
    }
  }
  imageStore(blocks, block, vec4(transparent > 0.5 ? 1.0 : 0.0));
}
#else
uniform float rangeLower;   // the transfer table's range: normalised = (raw - lower) / width
uniform float rangeWidth;
uniform int tableSize;      // entries of the table (the shader samples them linearly)

layout(std430, binding = 0) readonly buffer Level
{
  vec2 nodes[]; // (min, max) by Morton index
};
layout(std430, binding = 1) readonly buffer NonZero
{
  uint nonZeroBefore[]; // tableSize + 1 prefix counts of the entries with opacity > 0
};
layout(std430, binding = 2) buffer Count
{
  uint transparentLeaves;
};
layout(r8, binding = 0) uniform writeonly image3D leaves;

// Spreads the low 10 bits of v to every third bit (the core's Morton interleave, x in bit 0).
uint Spread(uint v)
{
  v &= 0x000003ffu;
  v = (v | (v << 16u)) & 0xff0000ffu;
  v = (v | (v << 8u)) & 0x0300f00fu;
  v = (v | (v << 4u)) & 0x030c30c3u;
  v = (v | (v << 2u)) & 0x09249249u;
  return v;
}

void main()
{
  ivec3 leaf = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(leaf, leafGrid)))
  {
    return;
  }
  uvec3 u = uvec3(leaf);
  vec2 range = nodes[Spread(u.x) | (Spread(u.y) << 1u) | (Spread(u.z) << 2u)];
  // The entries a sample value in [min, max] interpolates between (the shader reads the table at
  // value * (size - 1) texels), widened by one each way for rounding.
  float scale = float(tableSize - 1) / rangeWidth;
  float low = clamp((range.x - rangeLower) * scale, 0.0, float(tableSize - 1));
  float high = clamp((range.y - rangeLower) * scale, 0.0, float(tableSize - 1));
  int first = max(0, int(floor(low)) - 1);
  int last = min(tableSize - 1, int(ceil(high)) + 1);
  bool transparent = range.x <= range.y && nonZeroBefore[last + 1] == nonZeroBefore[first];
  imageStore(leaves, leaf, vec4(transparent ? 1.0 : 0.0));
  if (transparent)
  {
    atomicAdd(transparentLeaves, 1u);
  }
}
#endif
