#ifndef ArrayRanges_h
#define ArrayRanges_h

class vtkDataArray;

namespace mlsvtk
{
/**
 * Stores the ranges of a float or double array with 3 components, whose values were just written,
 * in the array's range cache: per component and of the L2 norm (vtkDataArray's PER_COMPONENT and
 * L2_NORM_RANGE), and their finite twins, which equal them since every value is finite. ParaView's
 * data information asks for all four after every update of a pipeline, and VTK computes each in
 * a serial pass of its own (0.6 s per deformation of a 1.2M-point mesh's Points and Displacement);
 * here one parallel pass finds them, with VTK's arithmetic, so the ranges shown are VTK's. Call it
 * after the array's last Modified(), which clears the cache. An array holding a non-finite value
 * or of another type is left to VTK.
 */
void storeRanges(vtkDataArray* array);
}

#endif
