// Min-max octree leaf pass: one workgroup per leaf (by Morton index). Its 64 invocations stride
// over the voxels the leaf's box covers (x fastest, so neighbouring invocations read
// neighbouring texels), each keeping a min and max, then reduce them in shared memory; the first
// writes the leaf's range, decoded to raw scalar values, into the level-0 buffer.
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

shared float lows[64];
shared float highs[64];

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
  // 2D grid of workgroups: the x group count is limited to 65535. Every test that returns early
  // depends on the workgroup alone, so no invocation skips the barriers of its group.
  uint index = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (index >= nodeCount)
  {
    return;
  }
  uint lane = gl_LocalInvocationID.x;
  ivec3 leaf = ivec3(Compact(index), Compact(index >> 1), Compact(index >> 2));
  // The core's padding convention: empty nodes are (+inf, -inf).
  float low = uintBitsToFloat(0x7f800000u);
  float high = uintBitsToFloat(0xff800000u);
  bool inside = all(lessThan(leaf, leafGrid));
  if (inside)
  {
    // Voxels [i*L, (i+1)*L] clamped to the volume: one voxel of overlap with the next leaf.
    ivec3 first = leaf * leafSize;
    ivec3 last = min(first + ivec3(leafSize), dims - ivec3(1));
    ivec3 extent = last - first + ivec3(1);
    int count = extent.x * extent.y * extent.z;
    for (int v = int(lane); v < count; v += 64)
    {
      int x = v % extent.x;
      int yz = v / extent.x;
      ivec3 voxel = first + ivec3(x, yz % extent.y, yz / extent.y);
      float texel = texelFetch(volume, voxel, 0).r;
      low = min(low, texel);
      high = max(high, texel);
    }
  }
  lows[lane] = low;
  highs[lane] = high;
  barrier();
  for (uint stride = 32u; stride > 0u; stride >>= 1)
  {
    if (lane < stride)
    {
      lows[lane] = min(lows[lane], lows[lane + stride]);
      highs[lane] = max(highs[lane], highs[lane + stride]);
    }
    barrier();
  }
  if (lane != 0u)
  {
    return;
  }
  vec2 range = vec2(lows[0], highs[0]);
  if (inside)
  {
    // Decoding is monotonic (decodeScale > 0), so decode only the extremes.
    low = lows[0];
    high = highs[0];
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
