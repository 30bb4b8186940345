# bezjoin workbench: nothing to set up without the GUI. The plain operations are
# in bezjoin_workbench.operations (usable from macros and freecadcmd).
