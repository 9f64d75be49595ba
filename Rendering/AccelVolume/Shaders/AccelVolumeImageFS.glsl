//VTK::System::Dec
// Shows a CPU mapper's premultiplied RGBA image over the scene (the image already stops
// at opaque geometry, so no depth test). With an image sample distance of 1 every fragment
// reads its own texel centre exactly; larger distances interpolate bilinearly.
//VTK::Output::Dec

uniform sampler2D image;       // the cast rectangle of the image
uniform vec2 viewportOrigin;
uniform vec2 viewportSize;
uniform vec2 imageSize;        // rays per row / column of the whole image
uniform vec2 rectangleOrigin;  // the rectangle's first pixel in the image
uniform vec2 rectangleSize;
uniform float colourScale;     // FinalColorWindow / Level: rgb * scale + bias * alpha
uniform float colourBias;
// Depth peeling of volumes (the pass's first volumetric stage): its second target, the front
// accumulation, gets nothing from the volume.
uniform int clearSecondTarget;
uniform int selectionMode;     // vtkHardwareSelector, as the slice mapper's resolve pass
uniform vec3 selectionColour;
// Shear-warp's intermediate image warped here: (u, v) = (warpU, warpV) . (x, y, 1) of the image
// position, pixel i of the intermediate image at i, zero outside (-1, warpLimit), as the CPU
// warp; the texture of textureExtent texels holds the image and one zero column and row.
uniform int warped;
uniform vec3 warpU;
uniform vec3 warpV;
uniform vec2 warpLimit;
uniform vec2 textureExtent;

void main()
{
  if (clearSecondTarget != 0)
  {
    gl_FragData[1] = vec4(0.0);
  }
  vec2 imagePosition = (gl_FragCoord.xy - viewportOrigin) / viewportSize * imageSize;
  vec4 colour;
  if (warped != 0)
  {
    vec2 uv = vec2(dot(warpU, vec3(imagePosition, 1.0)), dot(warpV, vec3(imagePosition, 1.0)));
    if (any(lessThanEqual(uv, vec2(-1.0))) || any(greaterThanEqual(uv, warpLimit)))
    {
      discard;
    }
    colour = texture(image, (uv + 0.5) / textureExtent);
  }
  else if (imageSize == viewportSize)
  {
    // One ray per pixel: fetch the texel itself (a filtered lookup could mix in a trace of its
    // neighbours through rounding, so images would depend on the rectangle's size).
    ivec2 texel = ivec2(floor(imagePosition - rectangleOrigin));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(rectangleSize))))
    {
      discard;
    }
    colour = texelFetch(image, texel, 0);
  }
  else
  {
    colour = texture(image, (imagePosition - rectangleOrigin) / rectangleSize);
  }
  if (colour.a <= 0.0 && colour.r <= 0.0 && colour.g <= 0.0 && colour.b <= 0.0)
  {
    discard;
  }
  if (selectionMode != 0)
  {
    if (selectionMode != 1 || colour.a <= 3.0 / 255.0)
    {
      discard;
    }
    gl_FragData[0] = vec4(selectionColour, 1.0);
    return;
  }
  if (colourScale != 1.0 || colourBias != 0.0)
  {
    colour.rgb = colour.rgb * colourScale + colourBias * colour.a; // unclamped, as VTK's

  }
  gl_FragData[0] = colour;
}
