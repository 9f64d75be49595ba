# Stand-ins for the VTK test data that run.sh's tests read, from ../shared/data (see run.sh).
# Usage: make_data.py <shared data dir> <output dir>
import gzip, numpy as np, vtk, os
from vtk.util import numpy_support as ns
import sys
D=sys.argv[1].rstrip('/')+'/'; O=sys.argv[2].rstrip('/')+'/Data/'
os.makedirs(O+'headsq', exist_ok=True)
def raw(name, dims, dt):
    a=np.frombuffer(gzip.open(D+name).read(), dtype=dt); return a.reshape(dims[2],dims[1],dims[0])
def image(a, spacing=(1,1,1), comps=1):
    im=vtk.vtkImageData()
    if comps==1: nz,ny,nx=a.shape
    else: nz,ny,nx,_=a.shape
    im.SetDimensions(nx,ny,nz); im.SetSpacing(*spacing)
    arr=ns.numpy_to_vtk(a.reshape(-1,comps) if comps>1 else a.ravel(), deep=1); arr.SetName('scalars')
    im.GetPointData().SetScalars(arr); return im
q=raw('headsq_quarter_64x64x93_int16.raw.gz',(64,64,93),'<i2')
for k in range(93): open(O+'headsq/quarter.%d'%(k+1),'wb').write(q[k].tobytes())
ip=raw('ironProt_68x68x68_uint8.raw.gz',(68,68,68),np.uint8)
w=vtk.vtkStructuredPointsWriter(); w.SetInputData(image(ip)); w.SetFileName(O+'ironProt.vtk'); w.SetFileTypeToBinary(); w.Write()
hm=gzip.open(D+'HeadMRVolume_48x62x42_uint8.raw.gz').read(); open(O+'HeadMRVolume.raw','wb').write(hm)
open(O+'HeadMRVolume.mhd','w').write("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\nElementSpacing = 4 4 4\nDimSize = 48 62 42\nElementType = MET_UCHAR\nElementDataFile = HeadMRVolume.raw\n")
# vase substitutes: teapot downsampled (a closed vessel, like the vase)
t=raw('boston_teapot_256x256x178_uint8.raw.gz',(256,256,178),np.uint8)[::2,::2,::2].copy()
wx=vtk.vtkXMLImageDataWriter(); wx.SetInputData(image(t)); wx.SetFileName(O+'vase_1comp.vti'); wx.Write()
t4=np.stack([t, (255-t.astype(int)).astype(np.uint8)*(t>20), (t//2), t],axis=-1).astype(np.uint8)
wx=vtk.vtkXMLImageDataWriter(); wx.SetInputData(image(t4,comps=4)); wx.SetFileName(O+'vase_4comp.vti'); wx.Write()
# tooth substitute: CT head 16-bit, downsampled
c=raw('cthead_256x256x113_uint16.raw.gz',(256,256,113),'<u2')[:,::2,::2].copy()
open(O+'tooth.raw','wb').write(c.tobytes())
open(O+'tooth.nhdr','w').write("NRRD0004\ntype: unsigned short\ndimension: 3\nsizes: %d %d %d\nspacings: 1 1 2\nencoding: raw\nendian: little\ndata file: tooth.raw\n"%(c.shape[2],c.shape[1],c.shape[0]))
# label atlas substitute: quantised MRI
m=raw('mri_t1_head_seg3d_160x232x160_uint8.raw.gz',(160,232,160),np.uint8)[::2,::2,::2]
lab=(m//26).astype(np.uint8)
wx=vtk.vtkXMLImageDataWriter(); wx.SetInputData(image(lab)); wx.SetFileName(O+'hncma-atlas.vti'); wx.Write()
# uneven rectilinear grid
rg=vtk.vtkRectilinearGrid(); n=(40,30,20); rg.SetDimensions(*n)
for ax,setter in enumerate((rg.SetXCoordinates,rg.SetYCoordinates,rg.SetZCoordinates)):
    x=np.cumsum(np.linspace(0.5,1.5,n[ax])); setter(ns.numpy_to_vtk(x,deep=1))
X,Y,Z=np.meshgrid(*(np.arange(k) for k in n),indexing='ij')
v=(np.sin(X/5.)*np.cos(Y/4.)+Z/20.).transpose(2,1,0).ravel()*100
arr=ns.numpy_to_vtk(v.astype(np.float32),deep=1); arr.SetName('scalars'); rg.GetPointData().SetScalars(arr)
wr=vtk.vtkRectilinearGridWriter(); wr.SetInputData(rg); wr.SetFileName(O+'RectGrid2.vtk'); wr.Write()
print('ok')
