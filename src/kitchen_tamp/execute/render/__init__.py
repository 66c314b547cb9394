"""What a run shows: ``replay.gif`` (``replay_video``), ``replay.html`` (``browser_replay``,
from ``scene_recording`` and ``untextured_meshes``) and ``joints.png`` (``joint_plot``)."""
