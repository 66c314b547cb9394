"""A kitchen as a scene: its scene file, the models and symbol map derived from it, and its layout.

``spec`` is what a scene file says, ``spec_reader`` reads it (TOML, every mistake
named), ``checks`` and ``region_checks`` check what no single key shows, ``models``
writes the URDFs, ``kitchen_map`` maps each symbol to bodies, links and regions (and
carries the domain's binding), ``regions`` computes where boxes may stand,
``start_poses`` where each box starts, ``layout`` builds the scene for a problem,
``kitchen_scene`` is that scene, and ``choice`` says which problem, domain and
kitchen a command line means.
"""
