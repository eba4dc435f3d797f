//! The names that mean each friction role ([`super::roles::Role`]), normalised
//! (lower case; spaces, `_`, `-` and `.` removed), most preferred first:
//! English, German, Spanish and Portuguese, and the names instruments'
//! exports use (`daqfx`, `zeit1standardmessrate`).

/// Names of [`Role::Time`](super::roles::Role::Time).
pub(super) const TIME: &[&str] = &[
    "time",
    "t",
    "times",
    "elapsedtime",
    "testtime",
    "timesec",
    "timestamp",
    "steptime",
    "zeit1standardmessrate",
    "time1defaultsamplerate",
    "zeit",
    "tiempo",
    "tempo",
];

/// Names of [`Role::FrictionForce`](super::roles::Role::FrictionForce).
pub(super) const FRICTION_FORCE: &[&str] = &[
    "fx",
    "frictionforce",
    "friction",
    "tangentialforce",
    "ft",
    "ff",
    "tangential",
    "fr",
    "ffriction",
    "forcex",
    "daqfx",
    "reibkraft",
    "reibungskraft",
    "tractionforce",
    "tangentialkraft",
    "fuerzadefricción",
    "fuerzadefriccion",
    "fuerzaderozamiento",
    "fuerzatangencial",
    "forçadeatrito",
    "forcadeatrito",
    "forçatangencial",
    "forcatangencial",
];

/// Names of [`Role::NormalForce`](super::roles::Role::NormalForce).
pub(super) const NORMAL_FORCE: &[&str] = &[
    "fz",
    "normalforce",
    "normalload",
    "fn",
    "load",
    "normal",
    "forcez",
    "daqfz",
    "normalkraft",
    "ballload",
    "fuerzanormal",
    "carganormal",
    "forçanormal",
    "forcanormal",
];

/// Names of [`Role::Velocity`](super::roles::Role::Velocity).
pub(super) const VELOCITY: &[&str] = &[
    "velocity",
    "v",
    "speed",
    "slidingvelocity",
    "slidingspeed",
    "linearvelocity",
    "linearspeed",
    "v1",
    "vx",
    "velocityx",
    "xvelocity",
    "meanspeed",
    "rollingspeed",
    "entrainmentspeed",
    "rotationalspeed",
    "spindlespeed",
    "discspeed",
    "rpm",
    "geschwindigkeit",
    "drehzahl",
    "rotaryvelocity",
    "velocidad",
    "velocidade",
];

/// Names of [`Role::Position`](super::roles::Role::Position).
pub(super) const POSITION: &[&str] = &[
    "position",
    "distance",
    "slidingdistance",
    "displacement",
    "pos",
    "x",
    "posx",
    "xposition",
    "positionx",
    "stroke",
    "strokeposition",
    "travel",
    "weg",
    "gleitweg",
    "distancia",
    "distância",
    "posición",
    "posicion",
    "posição",
    "posicao",
];

/// Names of [`Role::Temperature`](super::roles::Role::Temperature).
pub(super) const TEMPERATURE: &[&str] = &[
    "temperature",
    "temp",
    "t",
    "temp1",
    "lubetemp",
    "temperatur",
    "temperatura",
];

/// Names of [`Role::InstrumentCof`](super::roles::Role::InstrumentCof).
pub(super) const INSTRUMENT_COF: &[&str] = &[
    "cof",
    "mu",
    "µ",
    "μ",
    "coefficientoffriction",
    "frictioncoefficient",
    "coef",
    "daqcof",
    "tractioncoeff",
    "tractioncoefficient",
    "reibwert",
    "reibungskoeffizient",
    "reibungszahl",
    "coeficientedefricción",
    "coeficientedefriccion",
    "coeficientederozamiento",
    "coeficientedeatrito",
];

/// Names of [`Role::Step`](super::roles::Role::Step).
pub(super) const STEP: &[&str] = &[
    "step",
    "stepno",
    "stepnumber",
    "stepnr",
    "segment",
    "segmentno",
    "schritt",
];

/// Names of [`Role::Laps`](super::roles::Role::Laps).
pub(super) const LAPS: &[&str] = &[
    "laps",
    "lap",
    "lapcount",
    "revolutions",
    "revs",
    "turns",
    "rotations",
    "cycles",
    "cyclecount",
    "umdrehungen",
    "runden",
    "zyklen",
];

/// Names of [`Role::Angle`](super::roles::Role::Angle).
pub(super) const ANGLE: &[&str] = &[
    "angle",
    "angularposition",
    "rotaryangle",
    "rotaryposition",
    "theta",
    "winkel",
    "position",
];

/// Names of [`Role::WearDepth`](super::roles::Role::WearDepth).
pub(super) const WEAR_DEPTH: &[&str] = &[
    "wear",
    "weardepth",
    "linearwear",
    "wearloss",
    "depth",
    "lineardepth",
    "verschleiss",
    "verschleiß",
    "verschleisstiefe",
];
