"""Run inside the paraview GUI (paraview --dr --script=test_gui_visibility.py): issue 32, point 3.
Created from the Filters menu and applied with the Properties panel's Apply button, as a user
does (ParaView hides a filter's inputs on that Apply, as the filter's Visibility hint says): a
Constraint Region keeps the model it selects from shown; a Handle region's points are drawn
where the handle goes; MLS Deform hides its undeformed input (a surface) and keeps the regions
(drawn as points) shown. Writes 'ok' or the failures to the file named by MLSDEFORM_GUI_RESULT."""
import os
import time

from checks import check, write_result  # Testing/Python, on PYTHONPATH


try:
    from PyQt5.QtCore import QTimer
    from PyQt5.QtWidgets import QApplication, QMenu, QPushButton
    from paraview.simple import (GetActiveView, GetSources, LoadPlugin, OpenDataFile,
                                 Render, SetActiveSource, Show)
    from paraview import servermanager as sm
    LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False, ns=globals())
    app = QApplication.instance()

    def settle():
        for _ in range(5):
            app.processEvents()

    def from_menu(name, selected):
        """Selects the source and picks the filter in the main window's Filters > Alphabetical (other
        menus hold actions of the same name); a dialog that asks for the inputs (a filter of two
        input ports) is accepted as it opens, with its preselection."""
        SetActiveSource(selected)
        actions = []
        for _ in range(100):  # the menu enables its filters for the new selection after a while
            settle()
            windows = [w for w in app.topLevelWidgets() if w.objectName() == 'pqClientMainWindow']
            filters = windows[0].findChild(QMenu, 'menuFilters') if windows else None
            alphabetical = filters.findChild(QMenu, 'Alphabetical') if filters else None
            actions = [a for a in (alphabetical.actions() if alphabetical else [])
                       if a.objectName() == name and a.isEnabled()]
            if actions:
                break
            time.sleep(0.05)
        if not actions:
            raise RuntimeError('Filters > Alphabetical > %s: not found or not enabled' % name)

        def accept_dialog():
            dialog = app.activeModalWidget()
            if dialog is not None:
                dialog.accept()
        accepter = QTimer()  # accepts the input dialog whenever it opens, until the filter is made
        accepter.timeout.connect(accept_dialog)
        accepter.start(200)
        before = set(GetSources().values())
        actions[0].trigger()
        for _ in range(200):  # the new filter registers after the menu's reaction returns
            settle()
            made = [p for p in GetSources().values() if p not in before and p.GetXMLName() == name]
            if made:
                accepter.stop()
                return made[0]
            time.sleep(0.05)
        accepter.stop()
        raise RuntimeError('Filters > Alphabetical > %s made no %s' % (name, name))

    def apply():
        """Presses the Properties panel's Apply button."""
        settle()
        buttons = [b for w in app.topLevelWidgets() for b in w.findChildren(QPushButton, 'Accept') if b.isVisible()]
        check(len(buttons) == 1 and buttons[0].isEnabled(), 'the Apply button: %d shown, enabled %s'
              % (len(buttons), [b.isEnabled() for b in buttons]))
        if buttons:
            buttons[0].click()
        settle()
        Render()

    def shown(source):
        representation = sm.GetRepresentation(source, GetActiveView())
        return representation is not None and representation.Visibility == 1

    part = OpenDataFile(os.path.join(os.environ['MLSDEFORM_DATA_DIR'], 'fandisk.off'))
    Show(part)
    Render()
    xmin, xmax, ymin, ymax, zmin, zmax = part.GetDataInformation().GetBounds()
    height, margin = zmax - zmin, 0.01 * (zmax - zmin)

    def region(role, zlow, zhigh, **properties):
        r = from_menu('ConstraintRegion', part)
        r.Role = role
        r.Region = 'Box'
        r.Region.Position = [xmin - margin, ymin - margin, zlow]
        r.Region.Length = [xmax - xmin + 2 * margin, ymax - ymin + 2 * margin, zhigh - zlow]
        for key, value in properties.items():
            setattr(r, key, value)
        apply()
        return r

    fixed = region('Fixed', zmin - margin, zmin + 0.1 * height)
    check(shown(fixed) and shown(part), 'after applying the Fixed region: region shown %s, model shown %s'
          % (shown(fixed), shown(part)))
    handle = region('Handle', zmax - 0.25 * height, zmax + margin, Translation=[-0.15 * height, 0.0, 0.0])
    check(shown(handle) and shown(part), 'after applying the Handle region: region shown %s, model shown %s'
          % (shown(handle), shown(part)))
    # the Handle's points are drawn where the handle goes: moved by its translation (the
    # representation's transform; the region's output stays at rest, MLS Deform's input)
    settle()
    drawn = sm.GetRepresentation(handle, GetActiveView())
    check(max(abs(a - b) for a, b in zip(drawn.Position, handle.Translation)) <= 1e-12 * height and
          list(drawn.Orientation) == [0, 0, 0] and list(drawn.Scale) == [1, 1, 1],
          'the Handle points drawn at Position %s Orientation %s Scale %s, not moved by %s'
          % (list(drawn.Position), list(drawn.Orientation), list(drawn.Scale), list(handle.Translation)))
    deformed = from_menu('MLSDeform', part)
    deformed.Regions = [fixed, handle]
    deformed.NumberOfSamples = 500
    apply()
    check(shown(deformed) and not shown(part) and shown(fixed) and shown(handle),
          'after applying MLS Deform: deformed %s, model %s, Fixed %s, Handle %s (want True, False, True, True)'
          % (shown(deformed), shown(part), shown(fixed), shown(handle)))
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
