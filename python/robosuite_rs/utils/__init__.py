"""robosuite's ``robosuite.utils`` helpers, rewritten in plain NumPy.

``transform_utils`` (rotations, quaternions in (x, y, z, w) order, homogeneous poses) and
``camera_utils`` (camera matrices, depth maps, pixel <-> world projections, ``CameraMover``)
give the same names, signatures and numbers as robosuite 1.5.2's modules. Import them as
robosuite users do::

    from robosuite_rs.utils import transform_utils as T
    from robosuite_rs.utils import camera_utils as CU
"""
