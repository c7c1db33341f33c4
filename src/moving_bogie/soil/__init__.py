"""The ground under the track: a layered elastic half-space (docs/soil.md).

``profile`` reads the layers, ``layer`` builds each layer's stiffness matrix from the generated wave basis,
``flexibility`` the vertical surface flexibility U(k, omega), ``rayleigh`` the soil's surface-wave modes,
``strip`` the equivalent stiffness chi(k1, omega) of a strip on the soil, ``track`` and ``file`` the tracks on
the soil, ``critical`` their free waves and critical velocity, ``moving_load`` the steady response to a
moving constant load, ``plots`` the dispersion figure.
"""
