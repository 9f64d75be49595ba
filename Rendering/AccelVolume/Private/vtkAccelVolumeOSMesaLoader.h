// Registry of the OSMesa contexts this module created, read by the GLEW loader shim.
#ifndef vtkAccelVolumeOSMesaLoader_h
#define vtkAccelVolumeOSMesaLoader_h

// Adds (registered = true) or removes an OSMesaContext handle.
void vtkAccelVolumeRegisterOSMesaContext(void* context, bool registered);

#endif
