"""Issue 63 point 2: SaveData of a deformation of what ParaView's CGNS or Exodus reader read picks
the Mesh File Variant writer by default, so that the saved file is the source's variant (its
BCs, families, sets and solution kept), while other data still gets ParaView's own writers and
ParaView's writer stays available by name.
- CGNS: a file written by Debian's CGNS 3.4 (cgns_source.py: element-range BCs in families, a
  flow solution), read by ParaView's CGNS reader, deformed, saved with SaveData('...cgns'):
  the CGNS project's cgnscheck passes the variant and cgnsdiff -d finds only GridCoordinates
  changed.
- Exodus: a mesh with a node set and a side set (TestExodusMesh --write), read by ParaView's IOSS
  and Exodus II readers, saved with SaveData('...exo'): ncdump of the variant is the source's
  but for the coordinates.
- With the plugin's setting SaveDataWritesVariants off, ParaView's own writer is chosen.
Usage: pvpython test_save_data_default.py PLUGIN WORK TEST_EXODUS_MESH"""
import os
import re
import shutil
import subprocess
import sys

import cgns_source
from paraview import servermanager as sm
from paraview.modules.vtkRemotingServerManager import vtkSMParaViewPipelineController
from paraview.simple import (CGNSSeriesReader, CGNSWriter, ExodusIIReader, GetSettingsProxy, IOSSReader, LoadPlugin, SaveData,
                             Tetrahedralize, Wavelet)

from checks import check, finish

plugin, work, exodus_maker = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
factory = sm.vtkSMProxyManager.GetProxyManager().GetWriterFactory()


def deformation(reader, low, high):
    """MLS Deform of what reader read: the points below z = low fixed, those above z = high lifted."""
    fixed = ConstraintRegion(Input=reader, Role='Fixed')  # noqa: F821 (the plugin's)
    fixed.Region = 'Box'
    fixed.Region.Position, fixed.Region.Length = [-1, -1, -1], [10, 10, low + 1]
    handle = ConstraintRegion(Input=reader, Role='Handle', Translation=[0.2, 0.1, 0.3])  # noqa: F821
    handle.Region = 'Box'
    handle.Region.Position, handle.Region.Length = [-1, -1, high], [10, 10, 10]
    deform = MLSDeform(Input=reader, Regions=[fixed, handle], NumberOfSamples=40)  # noqa: F821
    deform.UpdatePipeline()
    return deform


def chosen(path, proxy):
    writer = factory.CreateWriter(path, proxy.SMProxy, 0)
    name = writer.GetXMLName() if writer else None
    if writer:
        writer.UnRegister(None)
    return name


# CGNS
source = cgns_source.make(os.path.join(work, 'source.cgns'))
reader = CGNSSeriesReader(FileNames=[source])
deform = deformation(reader, 0.5, 2.5)
offered = factory.GetSupportedFileTypes(deform.SMProxy, 0)
check(offered.startswith('A variant of the source mesh file'), "Save Data lists the variant's file type first (%s...)" % offered[:80])
check(chosen('x.cgns', deform) == 'AMeshVariantWriter', "SaveData('.cgns') of a deformation of a CGNS file picks the variant writer")
variant = os.path.join(work, 'variant', 'source.cgns')
os.makedirs(os.path.dirname(variant))
SaveData(variant, proxy=deform)
run = subprocess.run(['cgnscheck', variant], capture_output=True, text=True)
check(os.path.exists(variant) and run.returncode == 0 and 'ERROR' not in run.stdout,
      'cgnscheck passes the variant (exit %d: %s)' % (run.returncode, run.stdout.strip()[-200:]))
diff = subprocess.run(['cgnsdiff', '-d', source, variant], capture_output=True, text=True)
changed = [line for line in diff.stdout.splitlines() if line.strip()]
check(changed and all('GridCoordinates/Coordinate' in line for line in changed),
      'cgnsdiff -d: only the variant\'s GridCoordinates differ from the source (%s)' % changed[:6])
listed = subprocess.run(['cgnslist', variant], capture_output=True, text=True).stdout
check(all(family in listed for family in cgns_source.FAMILIES) and 'Pressure' in listed and listed.count('FamilyName') == 3,
      "the variant keeps the BCs' families and the flow solution")
own = os.path.join(work, 'paraview', 'own.cgns')
os.makedirs(os.path.dirname(own))
CGNSWriter(Input=deform, FileName=own).UpdatePipeline()
check(os.path.exists(own), "ParaView's own CGNS writer, named, still writes a new file")
# (the GUI makes a plugin's settings proxies as it loads the plugin; pvpython does not: made here)
vtkSMParaViewPipelineController().UpdateSettingsProxies(sm.ActiveConnection.Session)
settings = GetSettingsProxy('MLSDeformSettings')
settings.SaveDataWritesVariants = 0
check(chosen('x.cgns', deform) == 'CGNSWriter' and not factory.GetSupportedFileTypes(deform.SMProxy, 0).startswith('A variant'),
      "with the setting SaveDataWritesVariants off, Save Data of the deformation chooses ParaView's CGNS writer")
settings.SaveDataWritesVariants = 1
check(chosen('x.cgns', deform) == 'AMeshVariantWriter', 'and on again, the variant writer')
box = Tetrahedralize(Input=Wavelet(WholeExtent=[0, 4, 0, 4, 0, 4]))
check(chosen('x.cgns', box) == 'CGNSWriter' and not factory.GetSupportedFileTypes(box.SMProxy, 0).startswith('A variant'),
      "data not read from a solver's file gets ParaView's CGNS writer and no variant file type")

# Exodus II, through both of ParaView's readers
mesh = os.path.join(work, 'three.exo')
subprocess.run([exodus_maker, '--write', mesh], check=True)


def dump(path):
    """ncdump's text without the file's name and the coordinates' values."""
    text = subprocess.run(['ncdump', path], capture_output=True, text=True, check=True).stdout
    text = re.sub(r'^netcdf [^{]*', '', text)
    return re.sub(r'\n coord[xyz] =[^;]*;', '', text)


for opener in (IOSSReader, ExodusIIReader):
    reader = opener(FileName=mesh)
    deform = deformation(reader, 0.5, 0.9)
    check(chosen('x.exo', deform) == 'AMeshVariantWriter', "SaveData('.exo') after ParaView's %s picks the variant writer"
          % opener.__name__)
    variant = os.path.join(work, opener.__name__, 'three.exo')
    os.makedirs(os.path.dirname(variant))
    SaveData(variant, proxy=deform)
    check(os.path.exists(variant) and dump(variant) == dump(mesh) and
          subprocess.run(['cmp', '-s', variant, mesh]).returncode == 1 and 'ns_names' in dump(mesh) and 'ss_names' in dump(mesh),
          "%s: the variant is the source with only its coordinates changed (node and side sets kept)" % opener.__name__)
check(chosen('x.e', box) == 'ExodusIIWriter', "data not read from a solver's file gets ParaView's Exodus writer")
finish()
