"""Run inside the paraview GUI (paraview --dr --script=test_gui_panel.py): the plugin filters'
Properties panels. From the proxy definitions: every panel property sits in a group (the handle
motion's five are left to their own widget), the advanced set is as designed, and every
property's documentation opens with a short first sentence that states the range, the choices
or 'on or off'. From the built Qt panel (PyQt5 on the GUI's own widgets): the group headers and
the property widgets shown in order, before and after the gear (advanced) button, Constraint
Region's fields shown by Role and SelectionMode, and each widget's tooltip. From the session's
progress handler: the progress text each filter reports to the status bar.
Writes 'ok' or the failures to the file named by MLSDEFORM_GUI_RESULT."""
import os
import re
import time

from checks import check, write_result  # Testing/Python, on PYTHONPATH


# The panel sections per filter, in panel order; each group's properties in panel order.
GROUPS = {
    'MLSDeform': [
        ('Energies', ['StretchWeight', 'BendWeight', 'FixWeight', 'EnergyDiscretization']),
        ('Targets', ['ExactTargets', 'TargetBlendRadius']),
        ('Constraints', ['ExactConstraints', 'ConstraintWeight', 'ConstraintFormulation', 'MaxIterations', 'Tolerance',
                         'Acceleration']),
        ('Mesh Quality', ['MeshQuality']),
        ('Design Sensitivities', ['ComputeSensitivities', 'ObjectiveGradientArray']),
        ('Sampling', ['NumberOfSamples', 'VolumeSampleFraction', 'IntegrationPointRatio', 'LloydIterations', 'Cover',
                      'RandomSeed', 'FollowMeshGrading']),
        ('Basis', ['Basis']),
        ('2D Case', ['ExtrusionAxis'])],
    'ShellDeform': [
        ('Energies', ['StretchWeight', 'BendWeight', 'FixWeight']),
        ('Targets', ['ExactTargets', 'TargetBlendRadius']),
        ('Constraints', ['ExactConstraints', 'ConstraintWeight', 'ConstraintFormulation', 'MaxIterations', 'Tolerance',
                         'Acceleration']),
        ('Mesh Quality', ['MeshQuality']),
        ('Design Sensitivities', ['ComputeSensitivities', 'ObjectiveGradientArray'])],
    'ConstraintRegion': [
        ('Role and Weight', ['Role', 'Weight']),
        ('Constraint Group', ['ConstraintGroup', 'DistanceAxis', 'MinimumDistance']),
        ('Symmetry Plane', ['SymmetryOrigin', 'SymmetryNormal']),
        ('Selection', ['SelectionMode', 'Blocks', 'Sets', 'NumberOfLayers', 'CellSets', 'PrimitiveId', 'Region', 'InsideOut',
                       'SelectionArray', 'Range']),
        ('Design Variables', ['DesignVariables'])],
    'MLSSampler': [
        ('Samples', ['NumberOfSurfaceSamples', 'NumberOfVolumeSamples', 'IntegrationPointRatio']),
        ('Placement', ['LloydIterations', 'Cover', 'RandomSeed', 'FollowMeshGrading', 'SurfaceWeight',
                       'DenseSamplesPerSample', 'BoundsPadding'])],
    'PrimitiveDetector': [
        ('Primitive Types', ['DetectPlanes', 'DetectCylinders', 'DetectSpheres', 'DetectCones']),
        ('Fit Tolerances', ['Epsilon', 'ClusterEpsilon', 'NormalThreshold', 'MinimumSupport']),
        ('Search', ['Probability', 'RandomSeed'])],
    'DeformationQuality': [],
}
ADVANCED = {
    'MLSDeform': {'ConstraintFormulation', 'MaxIterations', 'Tolerance', 'Acceleration', 'EnergyDiscretization',
                  'VolumeSampleFraction', 'IntegrationPointRatio', 'LloydIterations', 'Cover', 'RandomSeed',
                  'FollowMeshGrading', 'TargetBlendRadius'},
    'ShellDeform': {'ConstraintFormulation', 'MaxIterations', 'Tolerance', 'Acceleration', 'TargetBlendRadius'},
    'ConstraintRegion': set(),
    'MLSSampler': {'IntegrationPointRatio', 'LloydIterations', 'Cover', 'RandomSeed', 'FollowMeshGrading',
                   'SurfaceWeight', 'DenseSamplesPerSample', 'BoundsPadding'},
    'PrimitiveDetector': {'ClusterEpsilon', 'NormalThreshold', 'MinimumSupport', 'Probability', 'RandomSeed'},
    'DeformationQuality': set(),
}
# Constraint Region's handle motion: its own widget, not part of these groups.
MOTION = {'Translation', 'Rotation', 'Scale', 'UseCentroid', 'Center'}
PROGRESS_TEXTS = {'MLSDeform': 'MLS Deform', 'ShellDeform': 'Shell Deform', 'ConstraintRegion': 'Constraint Region',
                  'MLSSampler': 'MLS Sampler', 'PrimitiveDetector': 'Primitive Detector',
                  'DeformationQuality': 'Deformation Quality'}


def first_sentence(text):
    """Up to the first period followed by a capital letter, as the tooltip's reader sees it first."""
    return re.split(r'(?<=\.)\s+(?=[A-Z])', ' '.join(text.split()))[0]


def properties(smproxy):
    """(name, property) of every property of the proxy, in definition order."""
    found = []
    it = smproxy.NewPropertyIterator()
    it.Begin()
    while not it.IsAtEnd():
        found.append((it.GetKey(), it.GetProperty()))
        it.Next()
    return found


def in_panel(prop):
    return not prop.IsA('vtkSMInputProperty') and not prop.GetIsInternal() and \
        prop.GetPanelVisibility() in ('default', 'advanced')


def domains(prop):
    found = []
    it = prop.NewDomainIterator()
    it.Begin()
    while not it.IsAtEnd():
        found.append(it.GetDomain())
        it.Next()
    return found


def number(value):
    """As the documentation writes it: 1000000, 0.0001."""
    return '%d' % value if value == int(value) else '%g' % value


def stated_values(prop):
    """What the first sentence must state: 'min-max' of a range, every choice of an enumeration,
    'on or off' for a boolean (None when the property has no such domain)."""
    for domain in domains(prop):
        if domain.IsA('vtkSMBooleanDomain'):
            return ['on or off']
        if domain.IsA('vtkSMEnumerationDomain'):
            return [domain.GetEntryText(i) for i in range(domain.GetNumberOfEntries())]
        if domain.IsA('vtkSMDoubleRangeDomain') or domain.IsA('vtkSMIntRangeDomain'):
            if domain.GetMaximumExists(0):
                return ['%s-%s' % (number(domain.GetMinimum(0)), number(domain.GetMaximum(0)))]
            return ['from %s' % number(domain.GetMinimum(0))]
    return None


def check_definitions(name, smproxy):
    groups = {}
    for i in range(smproxy.GetNumberOfPropertyGroups()):
        group = smproxy.GetPropertyGroup(i)
        members = [smproxy.GetPropertyName(group.GetProperty(j)) for j in range(group.GetNumberOfProperties())]
        groups.setdefault(group.GetXMLLabel(), []).extend(members)  # same label: one panel section
    designed = dict(GROUPS[name])
    check({label: set(members) for label, members in groups.items() if not set(members) <= MOTION} ==
          {label: set(members) for label, members in designed.items()},
          '%s: groups %s' % (name, groups))
    grouped = {member for members in groups.values() for member in members}
    advanced = set()
    for key, prop in properties(smproxy):
        doc = prop.GetDocumentation()
        description = doc.GetDescription() if doc else None
        check(description and description.strip(), '%s.%s has no documentation' % (name, key))
        if not description:
            continue
        sentence = first_sentence(description)
        check(len(sentence) <= 120, '%s.%s: first sentence of %d characters' % (name, key, len(sentence)))
        if not in_panel(prop) or key in MOTION:
            continue
        check(key in grouped, '%s.%s is in no group' % (name, key))
        if prop.GetPanelVisibility() == 'advanced':
            advanced.add(key)
        values = stated_values(prop)
        check(values is None or all(v in sentence for v in values),
              '%s.%s: the first sentence "%s" does not state %s' % (name, key, sentence, values))
    check(advanced == ADVANCED[name], '%s: advanced %s' % (name, sorted(advanced)))


# --- The Qt panel (PyQt5's names are imported below, inside the reporting try).
def process_events(app, seconds=0.5):
    end = time.time() + seconds
    while time.time() < end:
        app.processEvents()
        time.sleep(0.02)


def visible_proxy_widget(app, smproxy):
    """The Properties panel's visible pqProxyWidget that shows smproxy's properties."""
    names = {key.replace(' ', '') for key, prop in properties(smproxy) if in_panel(prop)}
    for widget in app.allWidgets():
        if widget.metaObject().className() == 'pqProxyWidget' and widget.isVisible() and \
                any(child.objectName() in names for child in widget.children()):
            return widget
    return None


def panel_rows(proxy_widget):
    """The visible group headers ('[label]') and property widgets (their property names), top to
    bottom: the panel as the user sees it."""
    rows = []
    for child in proxy_widget.children():
        if not isinstance(child, QWidget) or not child.isVisible():
            continue
        y = child.mapTo(proxy_widget, QPoint(0, 0)).y()
        header = [label.text() for label in child.findChildren(QLabel) if label.text().startswith('<html><b>')]
        if child.metaObject().className().startswith('pq') and child.objectName():
            rows.append((y, child.objectName()))
        elif header:
            rows.append((y, '[%s]' % re.sub('<[^>]*>', '', header[0])))
    return [row for _, row in sorted(rows)]


def expected_rows(name, shown):
    rows = []
    for label, members in GROUPS[name]:
        members = [member for member in members if member in shown]
        if members:
            rows += ['[%s]' % label] + members
    return rows


def set_advanced(app, on):
    """Presses the Properties panel's gear button (the search box's advanced button)."""
    for widget in app.allWidgets():
        if widget.metaObject().className() == 'pqPropertiesPanel':
            button = widget.findChild(QToolButton, 'AdvancedButton')
            if button.isChecked() != on:
                button.click()
    process_events(app)


def property_widget(proxy_widget, key):
    return proxy_widget.findChild(QWidget, key)


def choose(app, proxy_widget, key, text):
    """Picks text in the combo box of property key, as the user does (unchecked until Apply)."""
    combo = property_widget(proxy_widget, key).findChild(QComboBox)
    combo.setCurrentIndex(combo.findText(text))
    process_events(app)


def check_panel(app, name, proxy, shown_rows, what):
    SetActiveSource(proxy)
    process_events(app)
    proxy_widget = visible_proxy_widget(app, proxy.SMProxy)
    check(proxy_widget is not None, '%s: no visible panel (%s)' % (name, what))
    if proxy_widget is None:
        return None
    # (the handle motion's widgets, whatever they are, are not part of the design checked here)
    designed = {'[%s]' % label for label, _ in GROUPS[name]} | {key for _, members in GROUPS[name] for key in members}
    rows = [row for row in panel_rows(proxy_widget) if row in designed]
    check(rows == expected_rows(name, shown_rows), '%s panel (%s): %s' % (name, what, rows))
    for key, prop in properties(proxy.SMProxy):
        if key in rows:
            tooltip = ' '.join(property_widget(proxy_widget, key).toolTip().split())
            check(first_sentence(prop.GetDocumentation().GetDescription()) in tooltip,
                  '%s.%s: tooltip "%s"' % (name, key, tooltip[:200]))
    return proxy_widget


try:
    from PyQt5.QtCore import QPoint
    from PyQt5.QtWidgets import QApplication, QCheckBox, QComboBox, QLabel, QRadioButton, QToolButton, QWidget
    from paraview import servermanager as sm
    from paraview.simple import Delaunay3D, LoadPlugin, SetActiveSource, Sphere
    LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False, ns=globals())  # defines MLSDeform() etc.
    app = QApplication.instance()

    for name in GROUPS:
        check_definitions(name, sm.ProxyManager().GetPrototypeProxy('filters', name))

    # The status bar's progress text: what the session's progress handler reports while a filter
    # runs (ParaView shows it, less a leading 'vtk'). The handler passes at most one event per
    # 10 ms, so each filter updates alone, its inputs first, after a pause.
    handler = sm.ActiveConnection.Session.GetProgressHandler()
    handler.SetProgressInterval(0.01)
    texts = []
    handler.AddObserver('ProgressEvent', lambda caller, event: texts.append(caller.GetLastProgressText()))

    def progress_texts(proxy):
        time.sleep(0.05)
        del texts[:]
        proxy.UpdatePipeline()
        return texts[:]

    sphere = Sphere(ThetaResolution=16, PhiResolution=16)
    mesh = Delaunay3D(Input=sphere)
    fixed = ConstraintRegion(Input=sphere, Role='Fixed')
    fixed.Region = 'Box'
    fixed.Region.Position = [-1, -1, -1]
    fixed.Region.Length = [2, 2, 0.7]
    handle = ConstraintRegion(Input=sphere, Role='Handle')
    handle.Region = 'Box'
    handle.Region.Position = [-1, -1, 0.3]
    handle.Region.Length = [2, 2, 0.7]
    handle.Translation = [0.1, 0, 0]
    filters = {'ConstraintRegion': handle,
               'MLSDeform': MLSDeform(Input=sphere, Regions=[fixed, handle], NumberOfSamples=100),
               'ShellDeform': ShellDeform(Input=sphere, Regions=[fixed, handle]),
               'MLSSampler': MLSSampler(Input=sphere, NumberOfSurfaceSamples=60, NumberOfVolumeSamples=20),
               'PrimitiveDetector': PrimitiveDetector(Input=sphere),
               'DeformationQuality': DeformationQuality(Input=mesh)}
    for upstream in (sphere, mesh, fixed):
        upstream.UpdatePipeline()
    for name, proxy in filters.items():
        reported = progress_texts(proxy)
        check(reported[:1] == [PROGRESS_TEXTS[name]], '%s: progress texts %s' % (name, reported))

    # The panels as shown, without and with the gear (advanced) button.
    for advanced in (False, True):
        set_advanced(app, advanced)
        for name, proxy in filters.items():
            if name == 'ConstraintRegion' or not GROUPS[name]:  # Constraint Region below; no panel properties
                continue
            shown = {key for key, prop in properties(proxy.SMProxy)
                     if in_panel(prop) and (advanced or prop.GetPanelVisibility() == 'default')}
            check_panel(app, name, proxy, shown, 'advanced' if advanced else 'default')
    set_advanced(app, False)

    # Constraint Region: CellSets for the roles that make constraint sets, the selection fields
    # of the chosen mode only.
    panel = check_panel(app, 'ConstraintRegion', handle, {'Role', 'Weight', 'SelectionMode', 'Region', 'InsideOut', 'DesignVariables'},
                        'Handle, ImplicitFunction')
    if panel is not None:
        # issue 32, point 2: no label twice in the Handle's panel (the Region's box widget and the
        # handle motion each had a Translation, a Rotation and a Show Box; ParaView's box widget
        # itself a Rotation field and a Rotation check box), and the boxes' Show check boxes say which
        labels = [w for w in panel.findChildren(QLabel) + panel.findChildren(QCheckBox) + panel.findChildren(QRadioButton)
                  if w.isVisibleTo(panel) and w.text() and not w.text().startswith('<html>')]
        texts = [w.text() for w in labels]
        twice = sorted({text for text in texts if texts.count(text) > 1})
        check(not twice, 'ConstraintRegion panel (Handle): labels shown twice: %s' % twice)
        # issue 54, point 3: one visible choice of the box in the view
        check({'Show Selection Box', 'Box in the view:', 'Handle', 'Selection', 'None'} <= set(texts),
              'ConstraintRegion panel (Handle): the selection box\'s Show check box and the choice of box: %s' % texts)
        check(property_widget(panel, 'UseCentroid') is not None and property_widget(panel, 'UseCentroid').isVisibleTo(panel),
              'ConstraintRegion panel (Handle): UseCentroid hidden')
        choose(app, panel, 'Role', 'Rigid')
        check(property_widget(panel, 'UseCentroid') is None or not property_widget(panel, 'UseCentroid').isVisibleTo(panel),
              'ConstraintRegion panel (Rigid): UseCentroid shown')
        check_panel(app, 'ConstraintRegion', handle, {'Role', 'Weight', 'SelectionMode', 'CellSets', 'Region', 'InsideOut'},
                    'Rigid, ImplicitFunction')
        choose(app, panel, 'SelectionMode', 'CellLayers')
        check_panel(app, 'ConstraintRegion', handle, {'Role', 'Weight', 'SelectionMode', 'NumberOfLayers', 'CellSets'},
                    'Rigid, CellLayers')
        choose(app, panel, 'SelectionMode', 'ArrayRange')
        choose(app, panel, 'Role', 'Slip')
        check_panel(app, 'ConstraintRegion', handle, {'Role', 'Weight', 'SelectionMode', 'SelectionArray', 'Range'},
                    'Slip, ArrayRange')
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception:  # reported through the result file, the GUI swallows exceptions
    import traceback
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], traceback.format_exc())
