// Min-max octree leaf pass: one invocation per leaf (by Morton index) takes the min and max of
// the voxels its box covers, decoded to raw scalar values, into the level-0 buffer.
#version 430

layout(local_size_x = 64) in;

uniform sampler3D volume;
uniform ivec3 dims;      // voxels per axis
uniform ivec3 leafGrid;  // leaves per axis inside the volume
uniform int leafSize;    // voxels per leaf edge
uniform uint nodeCount;  // level-0 length (Morton index of the last leaf + 1)
uniform float decodeScale;
uniform float decodeOffset;
uniform bool roundTexel; // normalised integer textures: round to the stored integer first
uniform float margin;    // widening that keeps lossy encodings conservative

layout(std430, binding = 0) writeonly buffer Level
{
  vec2 nodes[]; // (min, max) by Morton index
};

// Gathers every third bit (the inverse of the core's Morton interleave, x in bit 0).
uint Compact(uint v)
{
  v &= 0x09249249u;
  v = (v ^ (v >> 2)) & 0x030c30c3u;
  v = (v ^ (v >> 4)) & 0x0300f00fu;
  v = (v ^ (v >> 8)) & 0xff0000ffu;
  v = (v ^ (v >> 16)) & 0x000003ffu;
  return v;
}

void main()
{
  // 2D dispatch: the x group count is limited to 65535.
  uint index = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u +
    gl_LocalInvocationID.x;
  if (index >= nodeCount)
  {
    return;
  }
  ivec3 leaf = ivec3(Compact(index), Compact(index >> 1), Compact(index >> 2));
  // The core's padding convention: empty nodes are (+inf, -inf).
  vec2 range = vec2(uintBitsToFloat(0x7f800000u), uintBitsToFloat(0xff800000u));
  if (all(lessThan(leaf, leafGrid)))
  {
    // Voxels [i*L, (i+1)*L] clamped to the volume: one voxel of overlap with the next leaf.
    ivec3 first = leaf * leafSize;
    ivec3 last = min(first + ivec3(leafSize), dims - ivec3(1));
    float low = uintBitsToFloat(0x7f800000u);
    float high = uintBitsToFloat(0xff800000u);
    for (int z = first.z; z <= last.z; ++z)
    {
      for (int y = first.y; y <= last.y; ++y)
      {
        for (int x = first.x; x <= last.x; ++x)
        {
          float texel = texelFetch(volume, ivec3(x, y, z), 0).r;
          low = min(low, texel);
          high = max(high, texel);
        }
      }
    }
    // Decoding is monotonic (decodeScale > 0), so decode only the extremes.
    if (roundTexel)
    {
      low = round(low * decodeScale);
      high = round(high * decodeScale);
    }
    else
    {
      low *= decodeScale;
      high *= decodeScale;
    }
    range = vec2(low + decodeOffset - margin, high + decodeOffset + margin);
  }
  nodes[index] = range;
}
