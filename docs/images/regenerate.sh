#!/bin/sh
# Renders the README's stills (the demo and the gallery) from the scenes in configs/, with
# discreel itself. Run from anywhere after building: sh docs/images/regenerate.sh
# The binary is build/bin/discreel unless DISCREEL names another.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
discreel=${DISCREEL:-$root/build/bin/discreel}

# still SCENE SECONDS [SIZE]: configs/SCENE.yaml at that time, 960x540 unless SIZE, to
# docs/images/SCENE.png
still() {
    "$discreel" render "$root/configs/$1.yaml" -o "$root/docs/images/$1.png" --at "$2" \
        --size "${3:-960x540}"
}

still demo 6.6
still galton 5.0
still cradle 1.92
still billiards 1.33
still grab 4.33
still rain 2.0
still polygons 3.0
still pyramid 2.6
still shapes 4.0
still bridge 1.3
still cradle-strings 1.2
still pendulum-wave 6.0 960x360
still windmill 2.0
