/**
 * @file    vtkAccelVolumeScalarEncoding.h
 * @brief   How the module stores volume scalars in a one-channel 3D texture (private):
 *          8/16-bit integers exactly in unsigned normalised textures (signed ones offset),
 *          everything else normalised to the finite data range in a 32-bit float texture.
 *          Shared by the slice mapper and the GPU octree builder so both decode alike.
 */
#ifndef vtkAccelVolumeScalarEncoding_h
#define vtkAccelVolumeScalarEncoding_h

#include <string>
#include <vector>

class vtkDataArray;

struct vtkAccelVolumeEncodedScalars
{
  int TextureType = 0;        // VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT or VTK_FLOAT
  const void* Data = nullptr; // the scalars themselves or one of the buffers below
  // raw value = texel * DecodeScale + DecodeOffset (integer encodings, texel in [0, 1]);
  // float encodings hold (value - Range[0]) / (Range[1] - Range[0]).
  double DecodeScale = 1.0;
  double DecodeOffset = 0.0;
  bool Normalized = false;
  double Range[2] = { 0.0, 1.0 };
  std::vector<unsigned char> Bytes;
  std::vector<unsigned short> Shorts;
  std::vector<float> Floats;
};

/**
 * Encodes one-component scalars; `range` is the finite data range used by the normalised
 * float encoding (NaN becomes its minimum, +/-Inf clamp to its ends). False with `error` for
 * types other than char, signed/unsigned char, (unsigned) short, int, float and double.
 */
bool vtkAccelVolumeEncodeScalars(vtkDataArray* scalars, const double range[2],
  vtkAccelVolumeEncodedScalars& encoded, std::string& error);

/**
 * The encoding vtkAccelVolumeEncodeScalars would choose (TextureType, DecodeScale, DecodeOffset,
 * Normalized, Range), without encoding anything: how to decode a texture made from these
 * scalars. False with `error` for unsupported types.
 */
bool vtkAccelVolumeScalarEncodingOf(vtkDataArray* scalars, const double range[2],
  vtkAccelVolumeEncodedScalars& encoding, std::string& error);

#endif
