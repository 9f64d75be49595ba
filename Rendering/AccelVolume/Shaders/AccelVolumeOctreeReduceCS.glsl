// Min-max octree reduce pass: one invocation per parent combines its 8 children, stored
// contiguously at 8p .. 8p+7 of the child level thanks to the Morton order.
#version 430

layout(local_size_x = 64) in;

uniform uint parentCount; // nodes at the parent level
uniform uint childCount;  // nodes at the child level (bounds the last parent's children)

layout(std430, binding = 0) readonly buffer Children
{
  vec2 children[];
};

layout(std430, binding = 1) writeonly buffer Parents
{
  vec2 parents[];
};

void main()
{
  uint index = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u +
    gl_LocalInvocationID.x;
  if (index >= parentCount)
  {
    return;
  }
  // Padding children are (+inf, -inf), so they never change the result.
  vec2 range = vec2(uintBitsToFloat(0x7f800000u), uintBitsToFloat(0xff800000u));
  uint end = min(8u * index + 8u, childCount);
  for (uint child = 8u * index; child < end; ++child)
  {
    vec2 node = children[child];
    range = vec2(min(range.x, node.x), max(range.y, node.y));
  }
  parents[index] = range;
}
