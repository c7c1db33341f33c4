"""The paper's artefacts: captions, figure recipes and the reproduce command's index page."""
